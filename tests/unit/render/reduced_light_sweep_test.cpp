// The light volume at reduced resolution for light-ball drags (reduced_light_sweep.h): close to
// the full sweep, never mistaken for it, and replaced by the full sweep at release.
#include "app/render/reduced_light_sweep.h"

#include <cmath>

#include <gtest/gtest.h>

#include "app/volume/scene_generators.h"

namespace cb {
namespace {

// Mean absolute difference over the voxels the full sweep does not leave fully lit.
double shadowedMeanAbsoluteError(const std::vector<float>& got, const std::vector<float>& ref) {
  double s = 0;
  size_t n = 0;
  for (size_t i = 0; i < ref.size(); ++i)
    if (ref[i] < 0.999f) {
      s += std::abs(double(got[i]) - double(ref[i]));
      ++n;
    }
  return n ? s / double(n) : 0.0;
}

// T at every voxel of the light bricks (the ones the renderer reads), in brick order.
std::vector<float> onLightBricks(const Volume& v, const LightVolume& lv) {
  std::vector<float> out;
  for (const glm::ivec3 b : lightBrickList(v)) {
    const VoxelBox box = v.brickBox(b);
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x) out.push_back(lv.at(x, y, z));
  }
  return out;
}

TEST(ReducedLightSweep, HalfResolutionIsCloseToTheFullSweepFromSeveralDirections) {
  Volume v = makeBundledCumulus(glm::ivec3(128), 1);
  ReducedLightSweep reduced;
  for (glm::vec3 pos :
       {glm::vec3(3.0f, 4.0f, 1.5f), glm::vec3(-4.0f, 1.0f, 2.0f), glm::vec3(0.5f, -3.0f, -3.0f)}) {
    Light light;
    light.direction = Light::directionTowards(pos);
    LightVolume full, coarse;
    sweepLightVolume(full, v, light, v.bounds());
    EXPECT_EQ(reduced.sweep(coarse, v, light, 2), v.bounds());
    const double error =
        shadowedMeanAbsoluteError(onLightBricks(v, coarse), onLightBricks(v, full));
    EXPECT_LT(error, 0.03) << pos.x << "," << pos.y << "," << pos.z;
    EXPECT_GT(error, 0.0) << "the coarse grid must differ somewhere (it is not the full sweep)";
  }
}

TEST(ReducedLightSweep, IsRecomputedInFullByTheNextSweep) {
  Volume v = makeSparsePuffs(glm::ivec3(64), 5);
  Light light;
  light.direction = Light::directionTowards(glm::vec3(2.0f, 3.0f, 1.0f));
  LightVolume lv, full;
  ReducedLightSweep reduced;
  reduced.sweep(lv, v, light, 2);
  EXPECT_FALSE(lv.matches(v, light)) << "a preview must never pass for the full light volume";
  EXPECT_EQ(sweepLightVolume(lv, v, light, {}), v.bounds()) << "no dirty box, yet all redone";
  sweepLightVolume(full, v, light, v.bounds());
  EXPECT_EQ(lv.toDense(), full.toDense());
}

}  // namespace
}  // namespace cb
