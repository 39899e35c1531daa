// cloudbrush-volume-to-vdb IN.cbvol OUT.vdb — writes a volume file as an OpenVDB fog volume
// (a FloatGrid named "density", GRID_FOG_VOLUME) with the same world placement, so Debian's
// vdb_render can render the same scene as `cloudbrush render` (used by `cloudbrush bench render`).
#include <cstdio>
#include <exception>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include "app/volume/volume_file.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s IN.cbvol OUT.vdb\n", argv[0]);
    return 2;
  }
  try {
    cb::Volume v = cb::loadVolume(argv[1]);
    openvdb::initialize();
    const glm::ivec3 d = v.dims();
    // Dense<float, LayoutXYZ> has z fastest; ours has x fastest, which is LayoutZYX.
    openvdb::CoordBBox bbox(openvdb::Coord(0, 0, 0), openvdb::Coord(d.x - 1, d.y - 1, d.z - 1));
    openvdb::tools::Dense<const float, openvdb::tools::LayoutXYZ> dense(bbox, v.data());
    auto grid = openvdb::FloatGrid::create(0.0f);
    openvdb::tools::copyFromDense(dense, grid->tree(), 0.0f);
    // Index-space integer coordinates are voxel centres: world = min + (i + ½)·size. VDB's
    // transform takes one uniform voxel size, so non-cubic voxels are refused.
    glm::vec3 size = v.voxelSize();
    if (std::abs(size.x - size.y) > 1e-6f * size.x || std::abs(size.x - size.z) > 1e-6f * size.x) {
      std::fprintf(stderr, "%s: voxels are not cubic; vdb export needs a uniform voxel size\n",
                   argv[1]);
      return 1;
    }
    auto xform = openvdb::math::Transform::createLinearTransform(double(size.x));
    glm::vec3 origin = v.worldMin() + 0.5f * size;
    xform->postTranslate(openvdb::Vec3d(origin.x, origin.y, origin.z));
    grid->setTransform(xform);
    grid->setName("density");
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
    openvdb::io::File(argv[2]).write({grid});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cloudbrush-volume-to-vdb: %s\n", e.what());
    return 1;
  }
  return 0;
}
