// Volume files: one JSON header line, then the raw densities of the stored box.
//
//   {"format":"cloudbrush-volume","version":2,"dims":[1024,256,1024],
//    "world_min":[-4,-1,-4],"world_max":[4,1,4],"stored_min":[448,64,448],
//    "stored_max":[576,192,576],"type":"float32","endian":"little","order":"x-fastest"}\n
//   <(stored_max - stored_min) per axis, multiplied: little-endian float32 of the voxels
//    stored_min <= (x,y,z) < stored_max, x fastest, then y, then z>
//
// dims is the whole grid (the virtual extent: voxel (i,j,k) covers world_min + [i,i+1)·
// (world_max - world_min)/dims on each axis); stored_min/stored_max are voxel indices of a
// half-open box inside it, and every voxel outside that box is zero. saveVolume stores the
// smallest box holding every voxel whose bits are not zero, so a cloud in a big empty sky is a
// file of the cloud's size, and an empty sky is the header alone (stored_min = stored_max =
// [0,0,0]). Version 1 files (no stored_min/stored_max: the whole grid, dims product floats)
// are still read.
//
// Anything wrong with a file (missing, not a volume, unknown version, bad dims or stored box,
// a stored box outside dims, truncated or trailing data, non-finite densities) raises
// VolumeFileError naming the file, the header field and the problem. Every size the header
// claims is checked against the bytes actually present and the limits (volume_file_header.h)
// before any voxel is allocated; bricks are then allocated only for non-zero voxels.
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
