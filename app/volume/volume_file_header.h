// The header line of a volume file (see volume_file.h) and every check of what it claims, so a
// reader can refuse a bad file before it allocates a single voxel.
//
// Errors are VolumeFileError "volume file 'NAME': header field 'FIELD': PROBLEM".
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "app/volume/volume.h"

namespace cb {

struct VolumeFileError : std::runtime_error {
  VolumeFileError(const std::string& file, const std::string& problem)
      : std::runtime_error("volume file '" + file + "': " + problem) {}
};

// Version written; version 1 (the whole grid stored) is still read.
constexpr int kVolumeFileVersion = 2;
// At most 1024³ voxels (4 GiB of float32): the largest grid `cloudbrush paint --grid` makes.
constexpr uint64_t kMaxVolumeFileVoxels = uint64_t(1) << 30;

// What a header claims, checked for internal consistency: dims are positive integers whose
// product and byte count fit in 64 bits; the world box is finite and not empty; the stored box
// (version 2) is made of non-negative integers with stored_min <= stored_max <= dims. Not yet
// checked against the file or the limits (see checkVolumeFileData/checkVolumeFileLimits).
struct VolumeFileHeader {
  int version = kVolumeFileVersion;
  uint64_t dims[3] = {0, 0, 0};  // the virtual extent
  glm::vec3 world_min{0.0f}, world_max{0.0f};
  uint64_t voxel_count = 0;  // dims[0] * dims[1] * dims[2]
  // The voxels whose floats the file holds (half-open); every other voxel is zero. Version 1:
  // the whole grid.
  uint64_t stored_min[3] = {0, 0, 0};
  uint64_t stored_max[3] = {0, 0, 0};
  uint64_t stored_voxels = 0;  // voxels of the stored box (0 when it is empty)
  uint64_t data_bytes = 0;     // stored_voxels * sizeof(float): the bytes after the header
};

// The header line (without the newline) that saveVolume writes for `volume` storing the voxels
// of `stored` (inside volume.bounds(); an empty box is written as [0,0,0]..[0,0,0]).
std::string volumeFileHeader(const Volume& volume, const VoxelBox& stored);

// Parses and checks the header line (without its newline) of the file called `name`.
VolumeFileHeader parseVolumeFileHeader(const std::string& line, const std::string& name);

// The data after the header must be exactly header.data_bytes long (the stored box's floats);
// `bytes_after_header` is what the file holds (`at_least`: the file holds more than that, its exact
// size is unknown).
void checkVolumeFileData(const VolumeFileHeader& header, uint64_t bytes_after_header,
                         const std::string& name, bool at_least = false);

// dims within kMaxVolumeDim per axis and kMaxVolumeFileVoxels in total.
void checkVolumeFileLimits(const VolumeFileHeader& header, const std::string& name);

// "AxBxC".
std::string formatDims(const VolumeFileHeader& header);
// "[x,y,z]..[x,y,z]" (stored_min..stored_max, half-open).
std::string formatStoredBox(const VolumeFileHeader& header);

}  // namespace cb
