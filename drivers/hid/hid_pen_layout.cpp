#include "drivers/hid/hid_pen_layout.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace cb::hid {

uint32_t equivalentUsage(uint32_t u) {
  if ((u >> 16) != page::kWacomVendor) return u;
  const uint16_t id = u & 0xFFFF;
  switch (id) {
    case 0x130:
      return pen_usage::kX;
    case 0x131:
      return pen_usage::kY;
    case 0x36:   // sense (proximity)
    case 0x5C:   // serial, high word
    case 0x77:   // tool type
    case 0x132:  // hover distance
      return u;
    default:
      return id < 0x100 ? usage(page::kDigitizer, id) : u;
  }
}

namespace {

bool isPenApplication(uint32_t app) {
  app = equivalentUsage(app);
  return app == pen_usage::kPen || app == pen_usage::kDigitizer;
}

FieldSlot slotFor(const Field& f, uint32_t element) {
  FieldSlot s;
  s.present = true;
  s.bit_offset = f.bit_offset + element * f.bit_size;
  s.bit_size = f.bit_size;
  s.is_signed = f.isSigned();
  s.logical_min = f.logical_min;
  s.logical_max = f.logical_max;
  s.physical_min = f.physical_min;
  s.physical_max = f.physical_max;
  s.unit = f.unit;
  s.unit_exponent = f.unit_exponent;
  return s;
}

}  // namespace

PenLayoutResult findPenLayout(const ReportDescriptor& desc) {
  PenLayoutResult result;
  // Candidate input reports: those holding X, Y and tip pressure in a pen application.
  std::vector<uint8_t> ids;
  for (const Field& f : desc.fields)
    if (f.type == ReportType::kInput && isPenApplication(f.application) && f.isVariable())
      for (uint32_t i = 0; i < f.count; ++i)
        if (equivalentUsage(f.usageAt(i)) == pen_usage::kTipPressure) ids.push_back(f.report_id);
  for (uint8_t id : ids) {
    PenLayout l;
    l.report_id = id;
    l.report_bytes = desc.reportBytes(ReportType::kInput, id);
    for (const Field& f : desc.fields) {
      if (f.type != ReportType::kInput || f.report_id != id || !f.isVariable() || f.isConstant())
        continue;
      for (uint32_t i = 0; i < f.count && i < f.usages.size() + 1; ++i) {
        if (f.usages.empty()) break;
        FieldSlot* target = nullptr;
        switch (equivalentUsage(f.usageAt(i))) {
          case pen_usage::kX:
            target = &l.x;
            break;
          case pen_usage::kY:
            target = &l.y;
            break;
          case pen_usage::kTipPressure:
            target = &l.pressure;
            break;
          case pen_usage::kTiltX:
            target = &l.tilt_x;
            break;
          case pen_usage::kTiltY:
            target = &l.tilt_y;
            break;
          case pen_usage::kWacomDistance:
            target = &l.distance;
            break;
          case pen_usage::kTipSwitch:
            target = &l.tip;
            break;
          case pen_usage::kBarrelSwitch:
            target = &l.barrel;
            break;
          case pen_usage::kSecondaryBarrelSwitch:
            target = &l.barrel2;
            break;
          case pen_usage::kEraser:
            target = &l.eraser;
            break;
          case pen_usage::kInvert:
            target = &l.invert;
            break;
          case pen_usage::kInRange:
            target = &l.in_range;
            break;
          case pen_usage::kWacomSense:
            target = &l.sense;
            break;
          case pen_usage::kToolSerial:
            target = &l.serial;
            break;
          case pen_usage::kWacomSerialHigh:
            target = &l.serial_high;
            break;
          case pen_usage::kWacomToolType:
            target = &l.tool_type;
            break;
          default:
            break;
        }
        if (target && !target->present) *target = slotFor(f, i);
        if (i + 1 >= f.usages.size() && i + 1 < f.count) break;  // no more distinct usages
      }
    }
    if (!l.x.present || !l.y.present) continue;
    if (!l.in_range.present && !l.sense.present && !l.tip.present) continue;
    for (const Field& f : desc.fields)
      if (f.type == ReportType::kFeature && f.report_id == 2 && isPenApplication(f.application))
        l.mode_report_id = 2;
    result.layout = l;
    return result;
  }
  result.error = ids.empty() ? "no input report with tip pressure in a pen or digitizer collection"
                             : "the pressure report lacks X, Y or a proximity/tip bit";
  return result;
}

int32_t kernelResolution(const FieldSlot& slot, bool is_angle) {
  int64_t logical = int64_t{slot.logical_max} - slot.logical_min;
  int64_t physical = int64_t{slot.physical_max} - slot.physical_min;
  int32_t exponent = slot.unit_exponent;
  if (logical <= 0 || physical <= 0) return 0;
  if (!is_angle) {
    if (slot.unit == 0x11) {  // centimetres -> millimetres
      exponent += 1;
    } else if (slot.unit == 0x13) {  // inches -> millimetres (x 25.4)
      if ((physical *= 254) > INT32_MAX) return 0;
      exponent -= 1;
    } else {
      return 0;
    }
  } else {
    if (slot.unit == 0x14) {  // degrees -> radians, as the kernel does: x 57.3
      if ((logical *= 573) > INT32_MAX) return 0;
      exponent += 1;
    } else if (slot.unit != 0x12) {
      return 0;
    }
  }
  // The kernel gives up (resolution 0) as soon as a 32-bit product would overflow.
  for (; exponent < 0; ++exponent)
    if ((logical *= 10) > INT32_MAX) return 0;
  for (; exponent > 0; --exponent)
    if ((physical *= 10) > INT32_MAX) return 0;
  if (logical > INT32_MAX || physical > INT32_MAX) return 0;
  return static_cast<int32_t>((logical + physical / 2) / physical);
}

PenDeviceInfo penDeviceInfo(const PenLayout& l, uint16_t vendor, uint16_t product,
                            const char* name) {
  PenDeviceInfo d;
  d.usb_vendor = vendor;
  d.usb_product = product;
  std::snprintf(d.name, sizeof d.name, "%s", name ? name : "");
  d.x_max = l.x.logical_max;
  d.y_max = l.y.logical_max;
  d.x_res = kernelResolution(l.x, false);
  d.y_res = kernelResolution(l.y, false);
  d.pressure_max = l.pressure.logical_max;
  if (l.tilt_x.present) {
    d.tilt_min = l.tilt_x.logical_min;
    d.tilt_max = l.tilt_x.logical_max;
    d.tilt_res = kernelResolution(l.tilt_x, true) * M_PI / 180.0;  // per radian -> per degree
  }
  d.distance_max = l.distance.present ? l.distance.logical_max : 0;
  return d;
}

}  // namespace cb::hid
