// Volume files: one JSON header line, then the raw density grid.
//
//   {"format":"cloudbrush-volume","version":1,"dims":[256,256,256],
//    "world_min":[-1,-1,-1],"world_max":[1,1,1],"type":"float32","endian":"little",
//    "order":"x-fastest"}\n
//   <dims.x*dims.y*dims.z little-endian float32, x fastest, then y, then z>
//
// Anything wrong with a file (missing, not a volume, unknown version, bad dims, truncated or
// trailing data, non-finite densities) raises VolumeFileError naming the file and the problem.
#pragma once

#include <stdexcept>
#include <string>

#include "app/volume/volume.h"

namespace cb {

struct VolumeFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr int kVolumeFileVersion = 1;

void saveVolume(const Volume& volume, const std::string& path);
Volume loadVolume(const std::string& path);

// The header line (without the newline) that saveVolume writes for `volume`.
std::string volumeFileHeader(const Volume& volume);

}  // namespace cb
