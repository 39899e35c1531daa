// Fuzz target: the volume file reader (outside bytes: volumes are exchanged between machines and
// given to `cloudbrush render --volume`). The input is read as a regular file (size known) and
// as a pipe (size unknown); a file is either refused with a message or read into a volume whose
// dims agree with the bytes it held. Headers that claim huge grids must be refused before any
// large allocation (libFuzzer's -malloc_limit_mb catches one).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>

#include "app/volume/volume_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  for (std::optional<uint64_t> known : {std::optional<uint64_t>(size), std::optional<uint64_t>()}) {
    std::istringstream in(bytes);
    try {
      const cb::Volume v = cb::readVolume(in, "fuzz.cbvol", known);
      const size_t header = bytes.find('\n') + 1;
      if (header == 0 || size - header != v.voxelCount() * sizeof(float)) std::abort();
      for (const float d : v.toDense())
        if (!std::isfinite(d)) std::abort();
    } catch (const cb::VolumeFileError& e) {
      if (std::string(e.what()).find("volume file 'fuzz.cbvol': ") != 0) std::abort();
    }
  }
  return 0;
}
