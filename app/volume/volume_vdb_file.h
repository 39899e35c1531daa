// OpenVDB export of a Volume, as Blender and Houdini import it: one FloatGrid named "density" of
// class GRID_FOG_VOLUME, whose linear transform puts index-space voxel (i,j,k) at the world-space
// centre of our voxel (i,j,k): world = world_min + (i + ½)·voxel_size. Voxels equal to 0 are
// background (inactive); every other voxel is active with its density.
//
// OpenVDB's transform has one uniform voxel size, so a volume with non-cubic voxels is refused
// with VolumeVdbError naming the file; write errors also name the file.
#pragma once

#include <stdexcept>
#include <string>

#include "app/volume/volume.h"

namespace cb {

struct VolumeVdbError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr const char* kVdbDensityGridName = "density";

void saveVolumeVdb(const Volume& volume, const std::string& path);

}  // namespace cb
