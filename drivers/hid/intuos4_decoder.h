// The Intuos4 protocol (the thesis's tablet, §3.2 and §5: a Wacom Intuos4 A4 with tilt and
// pressure): 10-byte reports with ID 2, as the kernel's drivers/hid/wacom_wac.c decodes them in
// wacom_intuos_inout() and wacom_intuos_general().
//
//   byte 1 = 0xC0..0xC3 : tool enters proximity; bytes 2..8 carry the tool id and 32-bit serial
//   byte 1 = 0x20/0x21  : tool in range but leaving (no contact)
//   byte 1 = 0x80/0x81  : tool leaves proximity
//   otherwise           : a tool packet of type (byte 1 >> 1) & 0x0F. Every type carries X and Y
//                         16+1 bits (bytes 2..5 and byte 9 bits 1/0) and hover distance 6 bits
//                         (byte 9 >> 2), which the kernel reports whatever the type:
//     0..3  general pen packet: pressure 11 bits (byte 6, byte 7 bits 7..6, byte 1 bit 0), tilt
//           X and Y 7 bits each (bytes 7..8, offset by 64), barrel buttons in byte 1 bits 1, 2;
//     5     rotation (Art Pen / marker, ABS_Z): 11 bits in byte 6 and byte 7 bits 7..5;
//     10    airbrush second packet: wheel 10 bits (ABS_WHEEL, byte 6, byte 7 bits 7..6) and tilt;
//     other types (mouse and lens-cursor packets, unhandled ones) carry position only.
//   Pressure, tilt and buttons not in a packet keep their last values, as evdev keeps them.
//   Mice and lens cursors (BTN_TOOL_MOUSE / BTN_TOOL_LENS) are not pens: their packets give
//   no samples. Tool ids use all 20 bits (bits 12..15 from byte 8, 16..19 from byte 7), serials
//   all 32 (bits 28..31 from byte 3).
//
// The tablet starts in a mouse-compatible mode; the host switches it to this protocol by
// setting feature report 2 to the value 2. Models, ranges, the mode switch and the tool-id
// table are data: config/devices/wacom-intuos4.toml (and wacom-intuos5.toml).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "drivers/core/pen_sample.h"
#include "drivers/devices/device_entry.h"
#include "drivers/hid/decode_result.h"

namespace cb::hid {

inline constexpr uint8_t kIntuos4PenReportId = 2;
inline constexpr size_t kIntuos4PacketBytes = 10;

class Intuos4Decoder {
 public:
  // `info`: the model's ranges (DeviceEntry::info); `tools`: which tool ids are erasers, mice
  // and lens cursors (null: every tool is a pen).
  Intuos4Decoder(const PenDeviceInfo& info, std::shared_ptr<const ToolTable> tools)
      : info_(info), tools_(std::move(tools)) {}
  DecodeResult decode(const uint8_t* report, size_t n, int64_t t_ns, PenSample& out);
  bool disconnect(int64_t t_ns, PenSample& out);
  // The last rotation (ABS_Z, Art Pen: -900..899) and airbrush wheel (ABS_WHEEL, 0..1023)
  // values, which PenSample has no fields for.
  int32_t rotation() const { return rotation_; }
  int32_t wheel() const { return wheel_; }

 private:
  PenDeviceInfo info_;
  std::shared_ptr<const ToolTable> tools_;
  int32_t rotation_ = 0, wheel_ = 0;
  uint32_t tool_id_ = 0;  // 0: no tool has entered
  uint32_t serial_ = 0;
  PenSample last_{};
};

}  // namespace cb::hid
