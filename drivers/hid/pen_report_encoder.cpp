#include "drivers/hid/pen_report_encoder.h"

namespace cb::hid {

namespace {

void putBits(std::vector<uint8_t>& r, size_t base, const FieldSlot& slot, uint32_t value) {
  if (!slot.present) return;
  for (uint32_t i = 0; i < slot.bit_size && i < 32; ++i) {
    const size_t bit = slot.bit_offset + i;
    if (base + bit / 8 >= r.size()) return;
    if ((value >> i) & 1u) r[base + bit / 8] |= static_cast<uint8_t>(1u << (bit % 8));
  }
}

}  // namespace

std::vector<uint8_t> encodePenReport(const PenLayout& l, const PenReportState& s) {
  std::vector<uint8_t> r(l.report_bytes, 0);
  size_t base = 0;
  if (l.report_id != 0) {
    r[0] = l.report_id;
    base = 1;
  }
  putBits(r, base, l.in_range, s.in_range);
  putBits(r, base, l.sense, s.sense);
  putBits(r, base, l.tip, s.tip && !s.eraser);
  putBits(r, base, l.eraser, s.eraser);
  putBits(r, base, l.invert, s.invert);
  putBits(r, base, l.barrel, s.barrel);
  putBits(r, base, l.barrel2, s.barrel2);
  putBits(r, base, l.x, static_cast<uint32_t>(s.x));
  putBits(r, base, l.y, static_cast<uint32_t>(s.y));
  putBits(r, base, l.pressure, static_cast<uint32_t>(s.pressure));
  putBits(r, base, l.tilt_x, static_cast<uint32_t>(s.tilt_x));
  putBits(r, base, l.tilt_y, static_cast<uint32_t>(s.tilt_y));
  putBits(r, base, l.distance, static_cast<uint32_t>(s.distance));
  putBits(r, base, l.serial, s.sense ? s.serial : 0);
  putBits(r, base, l.tool_type, s.sense ? s.tool_type : 0);
  return r;
}

std::vector<uint8_t> encodeIntuos4Enter(uint32_t id, uint32_t serial) {
  std::vector<uint8_t> d(10, 0);
  d[0] = 2;
  d[1] = 0xC2;
  d[2] = static_cast<uint8_t>(id >> 4);
  d[3] = static_cast<uint8_t>(((id & 0x0F) << 4) | ((serial >> 28) & 0x0F));
  d[4] = static_cast<uint8_t>(serial >> 20);
  d[5] = static_cast<uint8_t>(serial >> 12);
  d[6] = static_cast<uint8_t>(serial >> 4);
  d[7] = static_cast<uint8_t>(((serial & 0x0F) << 4) | ((id >> 16) & 0x0F));
  d[8] = static_cast<uint8_t>(((id >> 12) & 0x0F) << 4);
  return d;
}

std::vector<uint8_t> encodeIntuos4Pen(const PenReportState& s) {
  std::vector<uint8_t> d(10, 0);
  const uint32_t x = static_cast<uint32_t>(s.x), y = static_cast<uint32_t>(s.y);
  const uint32_t p = static_cast<uint32_t>(s.pressure);
  const uint32_t tx = static_cast<uint32_t>(s.tilt_x + 64),
                 ty = static_cast<uint32_t>(s.tilt_y + 64);
  d[0] = 2;
  d[1] = static_cast<uint8_t>(0xE0 | (s.barrel2 ? 4 : 0) | (s.barrel ? 2 : 0) | (p & 1));
  d[2] = static_cast<uint8_t>(x >> 9);
  d[3] = static_cast<uint8_t>(x >> 1);
  d[4] = static_cast<uint8_t>(y >> 9);
  d[5] = static_cast<uint8_t>(y >> 1);
  d[6] = static_cast<uint8_t>(p >> 3);
  d[7] = static_cast<uint8_t>((((p >> 1) & 3) << 6) | ((tx >> 1) & 0x3F));
  d[8] = static_cast<uint8_t>(((tx & 1) << 7) | (ty & 0x7F));
  d[9] = static_cast<uint8_t>((static_cast<uint32_t>(s.distance) << 2) | ((x & 1) << 1) | (y & 1));
  return d;
}

std::vector<uint8_t> encodeIntuos4Exit() {
  std::vector<uint8_t> d(10, 0);
  d[0] = 2;
  d[1] = 0x80;
  return d;
}

}  // namespace cb::hid
