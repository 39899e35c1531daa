// Volume files: one JSON header line, then the raw density grid.
//
//   {"format":"cloudbrush-volume","version":1,"dims":[256,256,256],
//    "world_min":[-1,-1,-1],"world_max":[1,1,1],"type":"float32","endian":"little",
//    "order":"x-fastest"}\n
//   <dims.x*dims.y*dims.z little-endian float32, x fastest, then y, then z>
//
// Anything wrong with a file (missing, not a volume, unknown version, bad dims, truncated or
// trailing data, non-finite densities) raises VolumeFileError naming the file, the header field
// and the problem. Every size the header claims is checked against the bytes actually present
// and the limits (volume_file_header.h) before any voxel is allocated.
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <string>

#include "app/volume/volume.h"
#include "app/volume/volume_file_header.h"

namespace cb {

void saveVolume(const Volume& volume, const std::string& path);
Volume loadVolume(const std::string& path);

// Reads a volume file from `in` (positioned at its first byte); `name` names it in errors.
// `size` is the file's total size in bytes when known (a regular file), else the data is read
// into a buffer first, so memory follows the bytes present, never what the header claims.
Volume readVolume(std::istream& in, const std::string& name, std::optional<uint64_t> size);

}  // namespace cb
