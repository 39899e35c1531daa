// Model → cloud: the generated ~70k-triangle torus, through an OBJ file and Assimp, fills the
// model's inside and stays inside it; open, degenerate, unreadable and huge mesh files are
// refused by name, leaving the volume untouched.
#include "app/tools/model_cloud.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "app/core/parallel_for.h"
#include "app/tools/mesh_loading.h"
#include "app/tools/procedural_mesh.h"
#include "app/tools/tool_error.h"

namespace cb {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("cb_model_cloud_" + name)).string();
}

constexpr float kMajor = 0.6f, kMinor = 0.25f, kAmplitude = 0.2f;

// Signed distance-like measure to the displaced torus in model units: < 0 inside. The tube
// radius varies with (u, v); this uses the exact radius at the point's own angles, which is the
// surface the mesh approximates (to within its chord error).
float torusInsideMargin(glm::vec3 p) {
  const float u = std::atan2(p.z, p.x);
  const float ring = std::sqrt(p.x * p.x + p.z * p.z) - kMajor;
  const float v = std::atan2(p.y, ring);
  const float tube = std::sqrt(ring * ring + p.y * p.y);
  return tube - displacedTorusTubeRadius(kMinor, kAmplitude, u, v);
}

TEST(ModelCloud, TorusCloudFillsTheInsideAndStaysWithinIt) {
  const TriangleMesh torus = makeDisplacedTorus(kMajor, kMinor, kAmplitude, 192, 184);
  ASSERT_EQ(torus.triangles.size(), 70656u);
  const std::string path = tempPath("torus.obj");
  writeObj(path, torus);

  Volume volume(glm::ivec3(128));
  ToolView view;
  view.camera = Camera::reference();
  view.size_fraction = 0.6f;
  const uint64_t before = volume.generation();
  const VoxelBox box = modelToCloud(path, view, ModelCloudParams{}, &volume);
  ASSERT_FALSE(box.empty());
  EXPECT_EQ(volume.dirtySince(before), box);

  const ModelPlacement placement = placeModel(torus, view, volume);
  const float voxel_model = volume.voxelSize().x / placement.scale;  // one voxel in model units
  const ModelCloudParams params;
  const float full_depth =
      (params.falloff_voxels + params.noise_erosion_voxels + 1.5f) * voxel_model;
  long long deep = 0, deep_full = 0, outside = 0, outside_dense = 0;
  for (int z = 0; z < 128; ++z)
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x) {
        const glm::vec3 world = volume.voxelToWorld(glm::vec3(x, y, z) + 0.5f);
        const glm::vec3 model = (world - placement.anchor) / placement.scale + placement.centre;
        const float margin = torusInsideMargin(model);
        const float density = volume.at(x, y, z);
        if (margin < -full_depth) {
          ++deep;
          deep_full += density >= params.peak_density * 0.999f;
        } else if (margin > 1.0f * voxel_model) {
          ++outside;
          outside_dense += density > 0.0f;
        }
      }
  ASSERT_GT(deep, 1000);
  EXPECT_GE(double(deep_full) / double(deep), 0.99) << deep_full << " of " << deep;
  EXPECT_EQ(outside_dense, 0) << "of " << outside << " voxels more than a voxel outside";
}

TEST(ModelCloud, SameMeshGivesTheSameBytesOnAnyThreadCount) {
  const TriangleMesh torus = makeDisplacedTorus(kMajor, kMinor, kAmplitude, 48, 40);
  std::vector<float> first;
  for (int threads : {1, 2, 8}) {
    setWorkerThreads(threads);
    Volume volume(glm::ivec3(64));
    ToolView view;
    view.camera = Camera::reference();
    meshToCloud(torus, view, ModelCloudParams{}, &volume);
    std::vector<float> bytes = volume.toDense();
    if (first.empty())
      first = bytes;
    else
      EXPECT_EQ(bytes, first) << threads << " threads";
  }
  setWorkerThreads(0);
}

void expectRefused(const std::string& path, ToolErrorKind kind) {
  Volume volume(glm::ivec3(32));
  volume.set(1, 2, 3, 0.5f);
  const uint64_t generation = volume.generation();
  ToolView view;
  try {
    modelToCloud(path, view, ModelCloudParams{}, &volume);
    ADD_FAILURE() << path << " was accepted";
  } catch (const ToolError& e) {
    EXPECT_EQ(e.kind, kind) << e.what();
  }
  EXPECT_EQ(volume.generation(), generation);
  double sum = 0;
  {
    const std::vector<float> volume_dense = volume.toDense();
    for (size_t i = 0; i < volume.voxelCount(); ++i) sum += volume_dense[i];
  }
  EXPECT_EQ(sum, 0.5);
}

TEST(ModelCloud, OpenAndDegenerateMeshesAreRefusedByName) {
  TriangleMesh open = makeDisplacedTorus(kMajor, kMinor, 0.0f, 24, 16);
  open.triangles.pop_back();
  const std::string open_path = tempPath("open.obj");
  writeObj(open_path, open);
  expectRefused(open_path, ToolErrorKind::kOpenMesh);

  // A closed tetrahedron squashed flat: every edge twice, no volume.
  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3f, 0.3f, 0}};
  flat.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  const std::string flat_path = tempPath("flat.obj");
  writeObj(flat_path, flat);
  expectRefused(flat_path, ToolErrorKind::kDegenerateMesh);

  const std::string garbage = tempPath("garbage.ply");
  std::ofstream(garbage) << "ply\nformat nonsense\n";
  expectRefused(garbage, ToolErrorKind::kMeshUnreadable);
  expectRefused(tempPath("missing.obj"), ToolErrorKind::kUnreadableFile);

  // A huge file is refused from its size, before Assimp reads a byte (a sparse file: no disk).
  const std::string huge = tempPath("huge.obj");
  std::ofstream(huge) << "v 0 0 0\n";
  std::filesystem::resize_file(huge, uintmax_t(kMaxMeshFileBytes) + 1);
  expectRefused(huge, ToolErrorKind::kMeshFileTooLarge);
  std::filesystem::remove(huge);
}

}  // namespace
}  // namespace cb
