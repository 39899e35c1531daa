// The Intuos4 protocol (the thesis's tablet, §3.2 and §5: a Wacom Intuos4 A4 with tilt and
// pressure): 10-byte reports with ID 2, as the kernel's drivers/hid/wacom_wac.c decodes them in
// wacom_intuos_inout() and wacom_intuos_general().
//
//   byte 1 = 0xC0..0xC3 : tool enters proximity; bytes 2..8 carry the tool id and 32-bit serial
//   byte 1 = 0x20/0x21  : tool in range but leaving (no contact)
//   byte 1 = 0x80/0x81  : tool leaves proximity
//   otherwise           : a general pen packet: X and Y 16+1 bits (bytes 2..5 and byte 9 bits
//                         1/0), hover distance 6 bits (byte 9 >> 2), pressure 11 bits
//                         (byte 6, byte 7 bits 7..6, byte 1 bit 0), tilt X and Y 7 bits each
//                         (bytes 7..8, offset by 64), barrel buttons in byte 1 bits 1 and 2.
//
// The tablet starts in a mouse-compatible mode; the host switches it to this protocol by
// setting feature report 2 to the value 2 (kIntuos4ModeReport / kIntuos4TabletMode).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "drivers/core/pen_sample.h"
#include "drivers/hid/decode_result.h"

namespace cb::hid {

inline constexpr uint8_t kIntuos4PenReportId = 2;
inline constexpr size_t kIntuos4PacketBytes = 10;
inline constexpr uint8_t kIntuos4ModeReport = 2;
inline constexpr uint8_t kIntuos4TabletMode = 2;

// Sizes of the Intuos4 family as the kernel's wacom_features table lists them (USB id 056a:xx).
struct Intuos4Model {
  uint16_t product;
  const char* name;
  int32_t x_max, y_max;
};
std::optional<Intuos4Model> intuos4Model(uint16_t vendor, uint16_t product);
// Ranges and resolutions the kernel gives an Intuos4 pen (200 units/mm, 2047 pressure levels,
// tilt -64..63 at 57 units per radian, distance 0..63).
PenDeviceInfo intuos4DeviceInfo(const Intuos4Model& model);

class Intuos4Decoder {
 public:
  explicit Intuos4Decoder(const PenDeviceInfo& info) : info_(info) {}
  DecodeResult decode(const uint8_t* report, size_t n, int64_t t_ns, PenSample& out);
  bool disconnect(int64_t t_ns, PenSample& out);

 private:
  PenDeviceInfo info_;
  uint32_t tool_id_ = 0;  // 0: no tool has entered
  uint32_t serial_ = 0;
  PenSample last_{};
};

}  // namespace cb::hid
