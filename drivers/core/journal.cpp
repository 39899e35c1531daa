#include "drivers/core/journal.h"

// The journal's codec: CRC-32 and the PenSample and Device payloads.
#include <array>
#include <cstring>

namespace cb {
namespace {

class ByteWriter {
 public:
  template <typename T>
  void put(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    uint8_t b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // x86-64 and aarch64 are little-endian; see header
    bytes.insert(bytes.end(), b, b + sizeof(T));
  }
  std::vector<uint8_t> bytes;
};

class ByteReader {
 public:
  ByteReader(const uint8_t* d, size_t n) : d_(d), n_(n) {}
  template <typename T>
  T get() {
    T v{};
    if (pos_ + sizeof(T) <= n_) std::memcpy(&v, d_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  bool exact() const { return pos_ == n_; }

 private:
  const uint8_t* d_;
  size_t n_;
  size_t pos_ = 0;
};

std::array<uint32_t, 256> makeCrcTable() {
  std::array<uint32_t, 256> t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}

}  // namespace

uint32_t crc32(const uint8_t* data, size_t n, uint32_t crc) {
  static const std::array<uint32_t, 256> table = makeCrcTable();
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

std::vector<uint8_t> encodePenSample(const PenSample& s) {
  ByteWriter w;
  w.put(s.t_ns);
  w.put(s.x_raw), w.put(s.y_raw), w.put(s.x_mm), w.put(s.y_mm);
  w.put(s.pressure_raw), w.put(s.pressure);
  w.put(s.tilt_x_raw), w.put(s.tilt_y_raw), w.put(s.tilt_x_deg), w.put(s.tilt_y_deg);
  w.put(s.distance_raw), w.put(s.distance);
  w.put(s.buttons), w.put(uint8_t(s.tool)), w.put(s.tool_id), w.put(s.tool_serial);
  w.put(uint8_t(s.in_proximity ? 1 : 0));
  return w.bytes;
}

std::optional<PenSample> decodePenSample(const std::vector<uint8_t>& p) {
  ByteReader r(p.data(), p.size());
  PenSample s;
  s.t_ns = r.get<int64_t>();
  s.x_raw = r.get<int32_t>(), s.y_raw = r.get<int32_t>();
  s.x_mm = r.get<double>(), s.y_mm = r.get<double>();
  s.pressure_raw = r.get<int32_t>(), s.pressure = r.get<float>();
  s.tilt_x_raw = r.get<int32_t>(), s.tilt_y_raw = r.get<int32_t>();
  s.tilt_x_deg = r.get<float>(), s.tilt_y_deg = r.get<float>();
  s.distance_raw = r.get<int32_t>(), s.distance = r.get<float>();
  s.buttons = r.get<uint32_t>();
  uint8_t tool = r.get<uint8_t>();
  s.tool_id = r.get<uint32_t>(), s.tool_serial = r.get<uint64_t>();
  s.in_proximity = r.get<uint8_t>() != 0;
  if (!r.exact() || tool > uint8_t(PenTool::kEraser)) return std::nullopt;
  s.tool = PenTool(tool);
  return s;
}

std::vector<uint8_t> encodeDeviceInfo(const PenDeviceInfo& d) {
  ByteWriter w;
  w.put(d.usb_vendor), w.put(d.usb_product);
  for (char c : d.name) w.put(c);
  w.put(d.x_max), w.put(d.y_max), w.put(d.x_res), w.put(d.y_res), w.put(d.pressure_max);
  w.put(d.tilt_min), w.put(d.tilt_max), w.put(d.tilt_res), w.put(d.distance_max);
  return w.bytes;
}

std::optional<PenDeviceInfo> decodeDeviceInfo(const std::vector<uint8_t>& p) {
  ByteReader r(p.data(), p.size());
  PenDeviceInfo d;
  d.usb_vendor = r.get<uint16_t>(), d.usb_product = r.get<uint16_t>();
  for (char& c : d.name) c = r.get<char>();
  d.name[sizeof(d.name) - 1] = 0;
  d.x_max = r.get<int32_t>(), d.y_max = r.get<int32_t>();
  d.x_res = r.get<double>(), d.y_res = r.get<double>();
  d.pressure_max = r.get<int32_t>();
  d.tilt_min = r.get<int32_t>(), d.tilt_max = r.get<int32_t>();
  d.tilt_res = r.get<double>();
  d.distance_max = r.get<int32_t>();
  if (!r.exact()) return std::nullopt;
  return d;
}

}  // namespace cb
