#include "drivers/hid/hid_pen_layout.h"

#include <algorithm>
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

bool isStylusCollection(uint32_t u) {
  u = equivalentUsage(u);
  return u == pen_usage::kStylus || u == pen_usage::kPen || u == pen_usage::kDigitizer;
}

bool isOtherToolCollection(uint32_t u) {
  u = equivalentUsage(u);
  return u == pen_usage::kFinger || u == pen_usage::kPuck;
}

// A field belongs to a pen when a Stylus/Pen/Digitizer collection encloses it and no Finger or
// Puck collection does (the innermost of each kind is what the parser keeps).
bool isPenField(const Field& f) {
  if (isOtherToolCollection(f.application) || isOtherToolCollection(f.physical) ||
      isOtherToolCollection(f.logical))
    return false;
  return isStylusCollection(f.application) || isStylusCollection(f.physical) ||
         isStylusCollection(f.logical);
}

FieldSlot slotFor(const Field& f, uint32_t element) {
  FieldSlot s;
  s.present = true;
  s.bit_offset = f.bit_offset + element * f.bit_size;
  s.bit_size = f.bit_size;
  s.is_signed = f.isSigned();
  s.null_state = f.hasNullState();
  s.logical_min = f.logical_min;
  s.logical_max = f.logical_max;
  s.physical_min = f.physical_min;
  s.physical_max = f.physical_max;
  s.unit = f.unit;
  s.unit_exponent = f.unit_exponent;
  return s;
}

FieldSlot* slotForUsage(PenLayout& l, uint32_t extended_usage) {
  switch (equivalentUsage(extended_usage)) {
    case pen_usage::kX:
      return &l.x;
    case pen_usage::kY:
      return &l.y;
    case pen_usage::kTipPressure:
      return &l.pressure;
    case pen_usage::kTiltX:
      return &l.tilt_x;
    case pen_usage::kTiltY:
      return &l.tilt_y;
    case pen_usage::kWacomDistance:
      return &l.distance;
    case pen_usage::kTipSwitch:
      return &l.tip;
    case pen_usage::kBarrelSwitch:
      return &l.barrel;
    case pen_usage::kSecondaryBarrelSwitch:
      return &l.barrel2;
    case pen_usage::kTabletPick:
      return &l.tablet_pick;
    case pen_usage::kTouch:
      return &l.touch;
    case pen_usage::kSecondaryTipSwitch:
      return &l.tip2;
    case pen_usage::kEraser:
      return &l.eraser;
    case pen_usage::kInvert:
      return &l.invert;
    case pen_usage::kInRange:
      return &l.in_range;
    case pen_usage::kWacomSense:
      return &l.sense;
    case pen_usage::kToolSerial:
    case pen_usage::kToolSerial2:  // hid-input maps both to MSC_SERIAL
      return &l.serial;
    case pen_usage::kWacomSerialHigh:
      return &l.serial_high;
    case pen_usage::kWacomToolType:
      return &l.tool_type;
    default:
      return nullptr;
  }
}

// The pen fields of one input report; the first field of each usage wins.
PenLayout layoutOfReport(const ReportDescriptor& desc, uint8_t id) {
  PenLayout l;
  l.report_id = id;
  l.report_bytes = desc.reportBytes(ReportType::kInput, id);
  for (const Field& f : desc.fields) {
    if (f.type != ReportType::kInput || f.report_id != id || !f.isVariable() || f.isConstant() ||
        f.usages.empty() || !isPenField(f))
      continue;
    // A variable field has one usage per element; the last one repeats (hid_add_field).
    const uint32_t elements = std::min<uint32_t>(f.count, static_cast<uint32_t>(f.usages.size()));
    for (uint32_t i = 0; i < elements; ++i) {
      const uint32_t u = f.usageAt(i);
      // hid-input (Linux 6.18, hidinput_configure_usage): Z is the hover distance only in a Pen
      // application; elsewhere it is ABS_Z, which a pen does not use.
      FieldSlot* target = u == pen_usage::kZ ? (f.application == pen_usage::kPen ? &l.z : nullptr)
                                             : slotForUsage(l, u);
      if (target && !target->present) *target = slotFor(f, i);
    }
  }
  return l;
}

bool isPenReport(const PenLayout& l) {
  return l.x.present && l.y.present &&
         (l.tip.present || l.in_range.present || l.sense.present || l.eraser.present ||
          l.invert.present || l.touch.present || l.tip2.present);
}

}  // namespace

PenLayoutResult findPenLayout(const ReportDescriptor& desc) {
  PenLayoutResult result;
  std::vector<uint8_t> ids;
  for (const Field& f : desc.fields)
    if (f.type == ReportType::kInput && isPenField(f) &&
        std::find(ids.begin(), ids.end(), f.report_id) == ids.end())
      ids.push_back(f.report_id);
  // Prefer a report with tip pressure; otherwise the first pen report (a tip-switch-only pen).
  std::optional<PenLayout> first;
  for (uint8_t id : ids) {
    PenLayout l = layoutOfReport(desc, id);
    if (!isPenReport(l)) continue;
    if (!first) first = l;
    if (l.pressure.present) {
      first = l;
      break;
    }
  }
  if (!first) {
    result.error =
        ids.empty()
            ? "no input field inside a Stylus, Pen or Digitizer collection"
            : "no pen report with X, Y and a Tip Switch, Touch, In Range, Invert or Eraser bit";
    return result;
  }
  for (const Field& f : desc.fields)
    if (f.type == ReportType::kFeature && f.report_id == 2 && isPenField(f))
      first->mode_report_id = 2;
  result.layout = first;
  return result;
}

namespace {

// The kernel computes in __s32 and is built with -fno-strict-overflow: a product wraps, and a
// wrapped result smaller than before ends the computation with resolution 0.
bool kernelMultiply(int32_t& value, int32_t factor) {
  const int32_t prev = value;
  value = static_cast<int32_t>(static_cast<uint32_t>(value) * static_cast<uint32_t>(factor));
  return value >= prev;
}

int32_t wrappingSub(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) - static_cast<uint32_t>(b));
}

}  // namespace

int32_t kernelResolution(const FieldSlot& slot, bool is_angle) {
  int32_t exponent = slot.unit_exponent;
  int32_t logical = wrappingSub(slot.logical_max, slot.logical_min);
  int32_t physical = wrappingSub(slot.physical_max, slot.physical_min);
  if (logical <= 0 || physical <= 0) return 0;  // "Check if the extents are sane"
  if (!is_angle) {
    if (slot.unit == 0x11) {  // centimetres -> millimetres
      exponent += 1;
    } else if (slot.unit == 0x13) {  // inches -> millimetres (x 25.4)
      if (!kernelMultiply(physical, 254)) return 0;
      exponent -= 1;
    } else {
      return 0;
    }
  } else {
    if (slot.unit == 0x14) {  // degrees -> radians, as the kernel does: x 57.3
      if (!kernelMultiply(logical, 573)) return 0;
      exponent += 1;
    } else if (slot.unit != 0x12) {
      return 0;
    }
  }
  for (; exponent < 0; ++exponent)
    if (!kernelMultiply(logical, 10)) return 0;
  for (; exponent > 0; --exponent)
    if (!kernelMultiply(physical, 10)) return 0;
  // DIV_ROUND_CLOSEST for positive operands: (x + d/2) / d, the sum in 32 bits as well.
  const auto sum =
      static_cast<int32_t>(static_cast<uint32_t>(logical) + static_cast<uint32_t>(physical / 2));
  return sum / physical;
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
  d.distance_max = l.distance.present ? l.distance.logical_max : l.z.present ? l.z.logical_max : 0;
  return d;
}

}  // namespace cb::hid
