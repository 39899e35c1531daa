#include "drivers/hid/intuos4_decoder.h"

#include <string>

#include "drivers/core/pen_units.h"
#include "drivers/hid/wacom_tool.h"

namespace cb::hid {

DecodeResult Intuos4Decoder::decode(const uint8_t* d, size_t n, int64_t t_ns, PenSample& out) {
  DecodeResult r;
  if (n == 0) {
    r.status = DecodeStatus::kRejected;
    r.reason = "empty report";
    return r;
  }
  if (d[0] != kIntuos4PenReportId) {
    r.status = DecodeStatus::kOtherReport;
    r.reason = "report ID " + std::to_string(d[0]) + " is not the Intuos4 pen report 2";
    return r;
  }
  if (n != kIntuos4PacketBytes) {
    r.status = DecodeStatus::kRejected;
    r.reason = std::string(n < kIntuos4PacketBytes ? "short" : "oversized") +
               " Intuos4 packet: " + std::to_string(n) + " bytes, expected 10";
    return r;
  }
  // Tool entering proximity: serial and tool id (wacom_intuos_inout).
  if ((d[1] & 0xFC) == 0xC0) {
    serial_ = ((d[3] & 0x0Fu) << 28) + (uint32_t{d[4]} << 20) + (uint32_t{d[5]} << 12) +
              (uint32_t{d[6]} << 4) + (d[7] >> 4);
    tool_id_ = (uint32_t{d[2]} << 4) | (d[3] >> 4) | ((d[7] & 0x0Fu) << 16) | ((d[8] & 0xF0u) << 8);
    r.status = DecodeStatus::kNoSample;
    return r;
  }
  // In range but leaving: contact and pressure drop, distance goes to its maximum.
  if ((d[1] & 0xFE) == 0x20) {
    if (!last_.in_proximity) {
      r.status = DecodeStatus::kNoSample;
      return r;
    }
    PenSample s = last_;
    s.t_ns = t_ns;
    s.buttons &= ~kPenTip;
    s.pressure_raw = 0;
    s.distance_raw = info_.distance_max;
    convertPenUnits(s, info_);
    last_ = out = s;
    r.status = DecodeStatus::kSample;
    return r;
  }
  // Tool leaving proximity.
  if ((d[1] & 0xFE) == 0x80) {
    const bool known = tool_id_ != 0;
    tool_id_ = 0;
    if (!known || !last_.in_proximity) {
      r.status = DecodeStatus::kNoSample;
      return r;
    }
    last_ = out = proximityOutSample(last_, t_ns);
    r.status = DecodeStatus::kSample;
    return r;
  }
  if (tool_id_ == 0) {  // the kernel drops packets until it knows the tool
    r.status = DecodeStatus::kNoSample;
    r.reason = "pen packet before the tool entered proximity";
    return r;
  }
  if (tools_ && tools_->isPuck(tool_id_)) {  // BTN_TOOL_MOUSE / BTN_TOOL_LENS: not a pen
    r.status = DecodeStatus::kNoSample;
    r.reason = "tool " + std::to_string(tool_id_) + " is a mouse or lens cursor, not a pen";
    return r;
  }
  // What evdev holds: the last sample while the tool stays, zeros after it entered (the exit
  // report reset every axis).
  PenSample s = last_.in_proximity ? last_ : PenSample{};
  s.t_ns = t_ns;
  // wacom_intuos_general(): position and distance for every packet type.
  s.x_raw = static_cast<int32_t>(((uint32_t{d[2]} << 8 | d[3]) << 1) | ((d[9] >> 1) & 1));
  s.y_raw = static_cast<int32_t>(((uint32_t{d[4]} << 8 | d[5]) << 1) | (d[9] & 1));
  s.distance_raw = d[9] >> 2;
  const auto tiltX = [&] {
    return static_cast<int32_t>((((d[7] << 1) & 0x7E) | (d[8] >> 7))) - 64;
  };
  const auto tiltY = [&] { return static_cast<int32_t>(d[8] & 0x7F) - 64; };
  const unsigned type = (d[1] >> 1) & 0x0F;
  switch (type) {
    case 0x00:
    case 0x01:
    case 0x02:
    case 0x03:  // general pen packet
      s.pressure_raw =
          static_cast<int32_t>((uint32_t{d[6]} << 3) | ((d[7] & 0xC0u) >> 5) | (d[1] & 1));
      s.tilt_x_raw = tiltX();
      s.tilt_y_raw = tiltY();
      s.buttons = 0;
      if (s.pressure_raw > 10) s.buttons |= kPenTip;  // the kernel's contact threshold
      if (d[1] & 2) s.buttons |= kPenStylus1;
      if (d[1] & 4) s.buttons |= kPenStylus2;
      break;
    case 0x0A:  // airbrush second packet: wheel and tilt
      wheel_ = static_cast<int32_t>((uint32_t{d[6]} << 2) | ((d[7] >> 6) & 3u));
      s.tilt_x_raw = tiltX();
      s.tilt_y_raw = tiltY();
      break;
    case 0x05: {  // rotation (Intuos3 and later: marker / Art Pen), in the kernel's unsigned math
      uint32_t t = (uint32_t{d[6]} << 3) | ((d[7] >> 5) & 7u);
      t = (d[7] & 0x20) ? ((t > 900) ? ((t - 1) / 2 - 1350) : ((t - 1) / 2 + 450)) : (450 - t / 2);
      rotation_ = static_cast<int32_t>(t);
      break;
    }
    default:  // position only
      break;
  }
  s.tool = tools_ && tools_->isEraser(tool_id_) ? PenTool::kEraser : PenTool::kPen;
  s.tool_id = wacomMangleToolId(tool_id_);
  s.tool_serial = serial_;
  s.in_proximity = true;
  convertPenUnits(s, info_);
  last_ = out = s;
  r.status = DecodeStatus::kSample;
  return r;
}

bool Intuos4Decoder::disconnect(int64_t t_ns, PenSample& out) {
  tool_id_ = 0;
  if (!last_.in_proximity) return false;
  last_ = out = proximityOutSample(last_, t_ns);
  return true;
}

}  // namespace cb::hid
