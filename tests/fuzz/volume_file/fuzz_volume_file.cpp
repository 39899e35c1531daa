// Fuzz target: the volume file reader (outside bytes: volumes are exchanged between machines and
// given to `cloudbrush render --volume`). The input is read as a regular file (size known) and
// as a pipe (size unknown); a file is either refused with a message or read into a volume whose
// stored box (version 2; the whole grid for version 1) lies inside its dims, agrees with the
// bytes the file held, and holds every non-zero voxel, all of them finite. Headers that claim
// huge grids or boxes must be refused before any large allocation (libFuzzer's -malloc_limit_mb
// catches one); a small file may claim a large virtual extent, so the volume is checked brick by
// brick, never made dense.
#include <bit>
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
      const size_t header_end = bytes.find('\n') + 1;
      if (header_end == 0) std::abort();
      const cb::VolumeFileHeader h =
          cb::parseVolumeFileHeader(bytes.substr(0, header_end - 1), "fuzz.cbvol");
      if (size - header_end != h.data_bytes) std::abort();
      cb::VoxelBox stored{
          glm::ivec3(int(h.stored_min[0]), int(h.stored_min[1]), int(h.stored_min[2])),
          glm::ivec3(int(h.stored_max[0]), int(h.stored_max[1]), int(h.stored_max[2]))};
      if (v.dims() != glm::ivec3(int(h.dims[0]), int(h.dims[1]), int(h.dims[2]))) std::abort();
      if (!stored.empty() && stored.intersect(v.bounds()) != stored) std::abort();
      for (const glm::ivec3 b : v.allocatedBrickList()) {
        const cb::VoxelBox box = v.brickBox(b);
        for (int z = box.lo.z; z < box.hi.z; ++z)
          for (int y = box.lo.y; y < box.hi.y; ++y)
            for (int x = box.lo.x; x < box.hi.x; ++x) {
              const float d = v.at(x, y, z);
              if (!std::isfinite(d)) std::abort();
              if (std::bit_cast<uint32_t>(d) != 0 && !stored.contains({x, y, z})) std::abort();
            }
      }
    } catch (const cb::VolumeFileError& e) {
      if (std::string(e.what()).find("volume file 'fuzz.cbvol': ") != 0) std::abort();
    }
  }
  return 0;
}
