#include "app/volume/volume_vdb_file.h"

#include <cmath>
#include <exception>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

namespace cb {

void saveVolumeVdb(const Volume& volume, const std::string& path) {
  const glm::vec3 size = volume.voxelSize();
  if (std::abs(size.x - size.y) > 1e-6f * size.x || std::abs(size.x - size.z) > 1e-6f * size.x)
    throw VolumeVdbError(path + ": voxels are not cubic (" + std::to_string(size.x) + " x " +
                         std::to_string(size.y) + " x " + std::to_string(size.z) +
                         "); an OpenVDB transform needs one uniform voxel size");
  try {
    openvdb::initialize();
    const glm::ivec3 d = volume.dims();
    // Our voxels are x fastest, then y, then z: OpenVDB's Dense LayoutXYZ (offset i + j·mY + k·mZ).
    const openvdb::CoordBBox bbox(openvdb::Coord(0, 0, 0),
                                  openvdb::Coord(d.x - 1, d.y - 1, d.z - 1));
    openvdb::tools::Dense<const float, openvdb::tools::LayoutXYZ> dense(bbox, volume.data());
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
    openvdb::tools::copyFromDense(dense, grid->tree(), /*tolerance=*/0.0f);
    // Integer index coordinates are voxel centres in OpenVDB, so the translation is the centre of
    // voxel (0,0,0).
    openvdb::math::Transform::Ptr xform =
        openvdb::math::Transform::createLinearTransform(double(size.x));
    const glm::vec3 origin = volume.worldMin() + 0.5f * size;
    xform->postTranslate(openvdb::Vec3d(origin.x, origin.y, origin.z));
    grid->setTransform(xform);
    grid->setName(kVdbDensityGridName);
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    openvdb::io::File file(path);
    file.write({grid});
    file.close();
  } catch (const openvdb::Exception& e) {
    throw VolumeVdbError(path + ": " + e.what());
  } catch (const std::exception& e) {
    throw VolumeVdbError(path + ": " + e.what());
  }
}

}  // namespace cb
