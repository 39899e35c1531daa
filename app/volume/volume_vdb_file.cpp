#include "app/volume/volume_vdb_file.h"

#include <cmath>
#include <exception>
#include <sstream>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include "app/core/atomic_file.h"

namespace cb {

void saveVolumeVdb(const Volume& volume, const std::string& path) {
  const glm::vec3 size = volume.voxelSize();
  if (std::abs(size.x - size.y) > 1e-6f * size.x || std::abs(size.x - size.z) > 1e-6f * size.x)
    throw VolumeVdbError(path + ": voxels are not cubic (" + std::to_string(size.x) + " x " +
                         std::to_string(size.y) + " x " + std::to_string(size.z) +
                         "); an OpenVDB transform needs one uniform voxel size");
  try {
    openvdb::initialize();
    // Brick by brick: zero voxels stay inactive background, as copyFromDense with tolerance 0
    // leaves them, and a sparse sky is never made dense.
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    openvdb::FloatGrid::Accessor voxels = grid->getAccessor();
    for (const glm::ivec3 b : volume.allocatedBrickList()) {
      const VoxelBox box = volume.brickBox(b);
      for (int z = box.lo.z; z < box.hi.z; ++z)
        for (int y = box.lo.y; y < box.hi.y; ++y)
          for (int x = box.lo.x; x < box.hi.x; ++x)
            if (const float v = volume.at(x, y, z); v != 0.0f)
              voxels.setValue(openvdb::Coord(x, y, z), v);
    }
    openvdb::tools::prune(grid->tree());
    // Integer index coordinates are voxel centres in OpenVDB, so the translation is the centre of
    // voxel (0,0,0).
    openvdb::math::Transform::Ptr xform =
        openvdb::math::Transform::createLinearTransform(double(size.x));
    const glm::vec3 origin = volume.worldMin() + 0.5f * size;
    xform->postTranslate(openvdb::Vec3d(origin.x, origin.y, origin.z));
    grid->setTransform(xform);
    grid->setName(kVdbDensityGridName);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    // OpenVDB does not check its output stream: a full disk would leave a torn file that looks
    // written. Serialise in memory, then write the bytes with the project's atomic writer
    // (app/core/atomic_file.h), which reports every failed write.
    std::ostringstream bytes(std::ios::binary);
    openvdb::io::Stream(bytes).write({grid});
    std::string error;
    if (!writeFileAtomically(path, bytes.view(), &error)) throw VolumeVdbError(error);
  } catch (const VolumeVdbError&) {
    throw;
  } catch (const openvdb::Exception& e) {
    throw VolumeVdbError(path + ": " + e.what());
  } catch (const std::exception& e) {
    throw VolumeVdbError(path + ": " + e.what());
  }
}

}  // namespace cb
