// Morphing: the ends are the source and the target, the total density follows the linear blend,
// in-betweens move (they are not a cross-fade) and the same inputs give the same bytes.
#include "app/tools/cloud_morph.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "app/tools/tool_error.h"

namespace cb {
namespace {

void addBall(Volume* v, glm::vec3 centre, float radius, float density) {
  const glm::ivec3 d = v->dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const float r = glm::distance(glm::vec3(x, y, z) + 0.5f, centre);
        if (r < radius) v->voxelForWrite(x, y, z) += density * (1.0f - r / radius);
      }
}

double total(const Volume& v) {
  double s = 0;
  {
    const std::vector<float> v_dense = v.toDense();
    for (size_t i = 0; i < v.voxelCount(); ++i) s += v_dense[i];
  }
  return s;
}

float maxDifference(const Volume& a, const Volume& b) {
  float m = 0;
  {
    const std::vector<float> a_dense = a.toDense(), b_dense = b.toDense();
    for (size_t i = 0; i < a.voxelCount(); ++i) m = std::max(m, std::abs(a_dense[i] - b_dense[i]));
  }
  return m;
}

struct Pair {
  Volume source{glm::ivec3(64)}, target{glm::ivec3(64)};
  Pair() {
    addBall(&source, {20, 30, 32}, 14, 0.9f);
    addBall(&target, {44, 28, 24}, 9, 1.0f);
    addBall(&target, {40, 40, 44}, 11, 0.7f);
  }
};

TEST(CloudMorph, EndsEqualSourceAndTarget) {
  Pair p;
  const CloudMorph plan(p.source, p.target);
  EXPECT_LE(maxDifference(plan.frame(0.0f), p.source), 1.0f / 255.0f);
  EXPECT_LE(maxDifference(plan.frame(1.0f), p.target), 1.0f / 255.0f);
}

TEST(CloudMorph, TotalDensityFollowsTheLinearBlendAndTheCloudMoves) {
  Pair p;
  const CloudMorph plan(p.source, p.target);
  const double ts = total(p.source), tt = total(p.target);
  for (float t : {0.1f, 0.25f, 0.5f, 0.75f, 0.9f}) {
    const Volume f = plan.frame(t);
    const double blend = (1 - t) * ts + t * tt;
    EXPECT_NEAR(total(f), blend, 0.05 * blend) << "t=" << t;
    // Not a cross-fade: the in-between differs from the per-voxel blend.
    Volume fade(p.source.dims());
    const std::vector<float> source = p.source.toDense(), target = p.target.toDense();
    std::vector<float> blended(source.size());
    for (size_t i = 0; i < blended.size(); ++i) blended[i] = (1 - t) * source[i] + t * target[i];
    fade.assignDense(blended.data());
    EXPECT_GT(maxDifference(f, fade), 0.05f) << "t=" << t;
  }
}

TEST(CloudMorph, SameInputsGiveTheSameBytes) {
  Pair p;
  const Volume a = morph(p.source, p.target, 0.4f);
  const Volume b = morph(p.source, p.target, 0.4f);
  EXPECT_EQ(0, std::memcmp(a.toDense().data(), b.toDense().data(), a.voxelCount() * sizeof(float)));
  // And swapping roles (more particles in the source) still plans and ends right.
  const CloudMorph back(p.target, p.source);
  EXPECT_LE(maxDifference(back.frame(1.0f), p.source), 1.0f / 255.0f);
}

TEST(CloudMorph, EmptyOrMismatchedVolumesAreRefusedByName) {
  Pair p;
  try {
    CloudMorph(p.source, Volume(glm::ivec3(64)));
    ADD_FAILURE();
  } catch (const ToolError& e) {
    EXPECT_EQ(e.kind, ToolErrorKind::kEmptyVolume);
  }
  try {
    CloudMorph(p.source, Volume(glm::ivec3(32)));
    ADD_FAILURE();
  } catch (const ToolError& e) {
    EXPECT_EQ(e.kind, ToolErrorKind::kMismatchedVolumes);
  }
}

}  // namespace
}  // namespace cb
