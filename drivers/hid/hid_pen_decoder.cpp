#include "drivers/hid/hid_pen_decoder.h"

#include <algorithm>
#include <string>

#include "drivers/core/pen_units.h"
#include "drivers/hid/wacom_tool.h"

namespace cb::hid {
namespace {

uint32_t readUnsigned(const uint8_t* p, size_t n, const FieldSlot& s) {
  return s.present ? extractBits(p, n, s.bit_offset, s.bit_size) : 0;
}

int32_t readValue(const uint8_t* p, size_t n, const FieldSlot& s) {
  if (!s.present) return 0;
  uint32_t v = extractBits(p, n, s.bit_offset, s.bit_size);
  return s.is_signed ? signExtend(v, std::min<uint32_t>(s.bit_size, 32)) : static_cast<int32_t>(v);
}

// hid-input.c, hidinput_hid_event(): for a variable field with logical_minimum <
// logical_maximum, a value outside the range is ignored when the field has a Null State
// (`value` is left unchanged, false returned) and clamped into the range otherwise.
bool applyHidInputRange(const FieldSlot& s, int32_t raw, int32_t& value) {
  if (!s.present) return false;
  if (s.logical_min < s.logical_max) {
    if (s.null_state && (raw < s.logical_min || raw > s.logical_max)) return false;
    raw = std::clamp(raw, s.logical_min, s.logical_max);
  }
  value = raw;
  return true;
}

}  // namespace

HidPenDecoder::HidPenDecoder(const PenLayout& layout, const PenDeviceInfo& info,
                             PenDriverRules rules, std::shared_ptr<const ToolTable> tools)
    : layout_(layout),
      info_(info),
      rules_(rules),
      tools_(std::move(tools)),
      hid_input_(PenStateUsages{layout.eraser.present, layout.invert.present, layout.tip.present,
                                layout.pressure.present, layout.in_range.present,
                                layout.touch.present || layout.tip2.present},
                 layout.pressure.logical_min, layout.pressure.logical_max) {}

DecodeResult HidPenDecoder::decode(const uint8_t* report, size_t n, int64_t t_ns, PenSample& out) {
  DecodeResult r;
  const size_t id_bytes = layout_.report_id != 0 ? 1 : 0;
  if (n == 0) {
    r.status = DecodeStatus::kRejected;
    r.reason = "empty report";
    return r;
  }
  if (id_bytes && report[0] != layout_.report_id) {
    r.status = DecodeStatus::kOtherReport;
    r.reason = "report ID " + std::to_string(report[0]) + " is not the pen report " +
               std::to_string(layout_.report_id);
    return r;
  }
  // The kernel's HID core (hid-core.c, hid_report_raw_event): a report shorter than the
  // descriptor says is refused (Linux 6.x: "Event data for report N was too short"), bytes past
  // its end are not read.
  if (n < layout_.report_bytes) {
    r.status = DecodeStatus::kRejected;
    r.reason = "short pen report: " + std::to_string(n) + " bytes, the descriptor says " +
               std::to_string(layout_.report_bytes);
    return r;
  }
  const uint8_t* p = report + id_bytes;
  const size_t pn = layout_.report_bytes - id_bytes;
  return rules_ == PenDriverRules::kWacom ? decodeWacom(p, pn, t_ns, out)
                                          : decodeHidInput(p, pn, t_ns, out);
}

DecodeResult HidPenDecoder::proximityOut(int64_t t_ns, PenSample& out) {
  DecodeResult r;
  if (!last_.in_proximity) {
    r.status = DecodeStatus::kNoSample;
    return r;
  }
  out = proximityOutSample(last_, t_ns);
  last_ = out;
  r.status = DecodeStatus::kSample;
  return r;
}

DecodeResult HidPenDecoder::decodeWacom(const uint8_t* p, size_t pn, int64_t t_ns, PenSample& out) {
  const bool in_range = readUnsigned(p, pn, layout_.in_range) != 0;
  // Wacom's vendor "sense" bit is proximity when present; otherwise In Range is.
  const bool sense = layout_.sense.present ? readUnsigned(p, pn, layout_.sense) != 0 : in_range;
  const bool invert = readUnsigned(p, pn, layout_.invert) != 0;
  const bool eraser_bit = readUnsigned(p, pn, layout_.eraser) != 0;

  // Serial and tool id as the kernel assembles them (wacom_wac_pen_event): the low word from
  // Tool Serial Number, the high word from Wacom's 0x5C, whose top 12 bits may carry id bits.
  const uint64_t serial_low = readUnsigned(p, pn, layout_.serial);
  const uint32_t serial_high = readUnsigned(p, pn, layout_.serial_high);
  const uint64_t serial = serial_low | (uint64_t{serial_high} << 32);
  uint32_t tool_id = readUnsigned(p, pn, layout_.tool_type);
  if (serial_high != 0 && (serial_high >> 20) == 1) tool_id |= serial_high & 0xFFFFF;
  if ((serial >> 52) == 1) tool_id = wacomMangleToolId(tool_id);

  if (tool_ == PenTool::kNone && in_range)
    tool_ = invert || (tools_ && tools_->isEraser(tool_id)) ? PenTool::kEraser : PenTool::kPen;

  if (!sense || tool_ == PenTool::kNone) {
    if (!sense) tool_ = PenTool::kNone;
    return proximityOut(t_ns, out);
  }

  PenSample s;
  s.t_ns = t_ns;
  s.x_raw = readValue(p, pn, layout_.x);
  s.y_raw = readValue(p, pn, layout_.y);
  s.pressure_raw = readValue(p, pn, layout_.pressure);
  s.tilt_x_raw = readValue(p, pn, layout_.tilt_x);
  s.tilt_y_raw = readValue(p, pn, layout_.tilt_y);
  s.distance_raw = readValue(p, pn, layout_.distance);
  if (readUnsigned(p, pn, layout_.tip) != 0 || eraser_bit) s.buttons |= kPenTip;
  if (readUnsigned(p, pn, layout_.barrel) != 0) s.buttons |= kPenStylus1;
  if (readUnsigned(p, pn, layout_.barrel2) != 0) s.buttons |= kPenStylus2;
  s.tool = tool_;
  // evdev carries MSC_SERIAL as a 32-bit value and ABS_MISC only alongside a serial.
  s.tool_serial = serial & 0xFFFFFFFFu;
  s.tool_id = serial != 0 ? tool_id : 0;
  s.in_proximity = true;
  convertPenUnits(s, info_);
  last_ = s;
  out = s;
  DecodeResult r;
  r.status = DecodeStatus::kSample;
  return r;
}

DecodeResult HidPenDecoder::decodeHidInput(const uint8_t* p, size_t pn, int64_t t_ns,
                                           PenSample& out) {
  // Axes: evdev keeps the last value it was given, so an ignored (null) value leaves it.
  applyHidInputRange(layout_.x, readValue(p, pn, layout_.x), state_.x_raw);
  applyHidInputRange(layout_.y, readValue(p, pn, layout_.y), state_.y_raw);
  applyHidInputRange(layout_.pressure, readValue(p, pn, layout_.pressure), state_.pressure_raw);
  applyHidInputRange(layout_.tilt_x, readValue(p, pn, layout_.tilt_x), state_.tilt_x_raw);
  applyHidInputRange(layout_.tilt_y, readValue(p, pn, layout_.tilt_y), state_.tilt_y_raw);
  applyHidInputRange(layout_.z, readValue(p, pn, layout_.z), state_.distance_raw);
  int32_t serial = static_cast<int32_t>(state_.tool_serial);
  if (applyHidInputRange(layout_.serial, readValue(p, pn, layout_.serial), serial))
    state_.tool_serial = static_cast<uint32_t>(serial);  // MSC_SERIAL, a 32-bit value

  PenStateValues v;
  v.eraser = readUnsigned(p, pn, layout_.eraser) != 0;
  v.invert = readUnsigned(p, pn, layout_.invert) != 0;
  v.tip = readUnsigned(p, pn, layout_.tip) != 0;
  v.in_range = readUnsigned(p, pn, layout_.in_range) != 0;
  v.pressure = state_.pressure_raw;
  const bool released_mid_report = hid_input_.update(v);
  updateKeys(p, pn);
  uint32_t buttons = 0;
  if (readUnsigned(p, pn, layout_.barrel) != 0) buttons |= kPenStylus1;
  if (stylus2_.down()) buttons |= kPenStylus2;

  if (hid_input_.tool() == PenTool::kNone) return proximityOut(t_ns, out);

  DecodeResult r;
  if (released_mid_report && last_.in_proximity)
    r.released = proximityOutSample(last_, t_ns);  // before this report's X/Y (lower priority)
  PenSample s = state_;
  s.t_ns = t_ns;
  s.buttons = buttons | (hid_input_.touch() ? kPenTip : 0u);
  s.tool = hid_input_.tool();
  s.tool_id = 0;  // hid-input has no tool id (ABS_MISC)
  s.in_proximity = true;
  convertPenUnits(s, info_);
  last_ = s;
  out = s;
  r.status = DecodeStatus::kSample;
  return r;
}

// The keys several usages feed, in the order the report carries the usages.
void HidPenDecoder::updateKeys(const uint8_t* p, size_t pn) {
  auto update = [&](HidInputKey<2>& key, const FieldSlot& a, const FieldSlot& b) {
    const bool a_first = !b.present || (a.present && a.bit_offset <= b.bit_offset);
    const FieldSlot& first = a_first ? a : b;
    const FieldSlot& second = a_first ? b : a;
    const bool present[2] = {first.present, second.present};
    const bool values[2] = {readUnsigned(p, pn, first) != 0, readUnsigned(p, pn, second) != 0};
    return key.update(present, values);
  };
  update(stylus2_, layout_.barrel2, layout_.tablet_pick);
  // Touch and Secondary Tip Switch come after the state usages (hidinput_usages_priorities):
  // a change of theirs sets BTN_TOUCH last, also while the rubber is the tool.
  if (update(other_touch_, layout_.touch, layout_.tip2) && hid_input_.tool() != PenTool::kNone)
    hid_input_.setTouch(other_touch_.down());
}

bool HidPenDecoder::disconnect(int64_t t_ns, PenSample& out) {
  tool_ = PenTool::kNone;
  hid_input_.reset();
  stylus2_.reset();
  other_touch_.reset();
  if (!last_.in_proximity) return false;
  out = proximityOutSample(last_, t_ns);
  last_ = out;
  return true;
}

}  // namespace cb::hid
