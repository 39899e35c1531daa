// Fuzz target: the Intuos4 protocol decoder over a stream of packets cut from the input (each
// chunk's length from its first byte, so short and oversized packets occur too).
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "drivers/hid/intuos4_decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The Intuos4 6x9's ranges (config/devices/wacom-intuos4.toml) and no tool table.
  cb::PenDeviceInfo info{};
  info.x_max = 44704;
  info.y_max = 27940;
  info.x_res = info.y_res = 200;
  info.pressure_max = 2047;
  info.tilt_min = -64;
  info.tilt_max = 63;
  info.distance_max = 63;
  cb::hid::Intuos4Decoder decoder(info, nullptr);
  cb::PenSample s;
  // Fixed 10-byte packets first (the well-formed path), then length-prefixed chunks.
  for (size_t pos = 0; pos + 10 <= size; pos += 10) {
    cb::hid::DecodeResult r = decoder.decode(data + pos, 10, 0, s);
    if (r.status == cb::hid::DecodeStatus::kSample &&
        (s.pressure_raw < 0 || s.pressure_raw > 2047 || s.tilt_x_raw < -64 || s.tilt_x_raw > 63 ||
         s.distance_raw > 63))
      std::abort();
  }
  size_t pos = 0;
  while (pos < size) {
    const size_t n = std::min<size_t>(data[pos] % 16, size - pos - 1);
    cb::hid::DecodeResult r = decoder.decode(data + pos + 1, n, 0, s);
    if (r.status == cb::hid::DecodeStatus::kRejected && r.reason.empty()) std::abort();
    pos += n + 1;
  }
  decoder.disconnect(0, s);
  return 0;
}
