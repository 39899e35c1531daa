#include "app/mapping/stroke_mapper.h"

#include <gtest/gtest.h>
#include <cstring>

#include "app/core/parallel_for.h"
#include "app/mapping/reference_strokes.h"
#include "opacity_projection.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 192;  // footprint: one pixel is about one 128³ voxel at the canvas

MappingConfig smallConfig() {
  MappingConfig c;
  c.circles.initial_diameter_px = 128 * kW / 1280;  // the thesis's 128 px at 1280 wide
  return c;
}

StrokeMapper& mapper() {
  static StrokeMapper m(smallConfig());
  m.setQuiet(true);
  return m;
}

bool hasWarning(const MappingReport& r, const std::string& text) {
  for (const std::string& w : r.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

// Silhouette and side-view checks run through the real renderer: stroke_mapper_render_test.

TEST(StrokeMapper, EveryLeftoverPixelIsMapped) {
  StrokeResult s = makeThickStroke(kW, kH, 12);
  Volume v(glm::ivec3(128));
  MappingReport r = mapper().map(s, v, MappingMethod::kHybrid);
  ASSERT_GT(r.edges.leftover_pixels, 0);
  EXPECT_EQ(r.edges.mapped_pixels, r.edges.leftover_pixels);
  // And each is visible from the paint view: some density on its ray.
  std::vector<float> opacity = test::projectOpacity(v, s.view.camera, kW, kH);
  std::vector<uint8_t> covered(s.footprint.values.size(), 0);
  for (const Circle& c : r.circles)
    for (int y = 0; y < kH; ++y) {
      int x0, x1;
      if (circleRowSpan(c.centre, c.radius, y, &x0, &x1))
        for (int x = std::max(0, x0); x <= std::min(kW - 1, x1); ++x) covered[y * kW + x] = 1;
    }
  long long leftover = 0, visible = 0;
  for (size_t i = 0; i < covered.size(); ++i)
    if (s.footprint.values[i] > 0.05f && !covered[i]) {
      ++leftover;
      visible += opacity[i] > 0.0f;
    }
  EXPECT_EQ(leftover, r.edges.leftover_pixels);
  EXPECT_GE(double(visible), 0.99 * double(leftover));
}

TEST(StrokeMapper, ByteIdenticalOnOneTwoAndEightThreads) {
  StrokeResult s = makeThickStroke(kW, kH, 14);
  std::vector<std::vector<float>> results;
  for (MappingMethod method : {MappingMethod::kHybrid, MappingMethod::kRayMarching}) {
    results.clear();
    for (int threads : {1, 2, 8}) {
      setWorkerThreads(threads);
      Volume v(glm::ivec3(128));
      mapper().map(s, v, method);
      results.push_back(v.toDense());
    }
    setWorkerThreads(0);
    for (size_t i = 1; i < results.size(); ++i)
      EXPECT_EQ(0, std::memcmp(results[0].data(), results[i].data(), results[0].size() * 4))
          << toString(method) << " differs on thread count #" << i;
  }
}

TEST(StrokeMapper, StrokeIndexSeedsTheScatter) {
  StrokeResult a = makeThickStroke(kW, kH, 15), b = a;
  b.stroke_index = a.stroke_index + 1;
  Volume va(glm::ivec3(128)), vb(glm::ivec3(128));
  mapper().map(a, va);
  mapper().map(b, vb);
  EXPECT_NE(0, std::memcmp(va.toDense().data(), vb.toDense().data(), va.voxelCount() * 4));
}

TEST(StrokeMapper, MergesWithMaxAndMarksTheDirtyBox) {
  StrokeResult s = makeThickStroke(kW, kH, 16);
  Volume v(glm::ivec3(128));
  const uint64_t before = v.generation();
  v.fill(0.0f);
  const uint64_t filled = v.generation();
  MappingReport r = mapper().map(s, v);
  ASSERT_FALSE(r.dirty.empty());
  EXPECT_GT(v.generation(), filled);
  EXPECT_GT(filled, before);
  EXPECT_EQ(v.dirtySince(filled), r.dirty);
  // Nothing outside the dirty box changed.
  for (int z = 0; z < 128; ++z)
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x) {
        if (!r.dirty.contains({x, y, z})) {
          ASSERT_EQ(v.at(x, y, z), 0.0f) << x << "," << y << "," << z;
        }
      }
  // Mapping again is a no-op under max; mapping onto a denser volume keeps it.
  std::vector<float> once = v.toDense();
  mapper().map(s, v);
  EXPECT_EQ(0, std::memcmp(once.data(), v.toDense().data(), once.size() * 4));
  Volume dense(glm::ivec3(128));
  dense.fill(1.0f);
  mapper().map(s, dense);
  {
    const std::vector<float> dense_dense = dense.toDense();
    for (size_t i = 0; i < dense.voxelCount(); ++i) ASSERT_EQ(dense_dense[i], 1.0f);
  }
  // The overlay's circles are the last HMM stroke's.
  EXPECT_EQ(mapper().lastCircles().size(), r.circles.size());
}

TEST(StrokeMapperBadInput, EmptyFootprint) {
  StrokeResult s = makeThickStroke(kW, kH, 17);
  std::fill(s.footprint.values.begin(), s.footprint.values.end(), 0.0f);
  Volume v(glm::ivec3(64));
  const uint64_t g = v.generation();
  MappingReport r = mapper().map(s, v);
  EXPECT_TRUE(r.dirty.empty());
  EXPECT_EQ(v.generation(), g);
  EXPECT_TRUE(hasWarning(r, "no pixel above the empty threshold"));
  s.footprint = Footprint();
  r = mapper().map(s, v);
  EXPECT_TRUE(hasWarning(r, "malformed"));
}

TEST(StrokeMapperBadInput, OnePixel) {
  StrokeResult s = makeThickStroke(kW, kH, 18);
  std::fill(s.footprint.values.begin(), s.footprint.values.end(), 0.0f);
  s.footprint.at(kW / 2, kH / 2) = 1.0f;
  Volume v(glm::ivec3(64));
  MappingReport r = mapper().map(s, v);
  EXPECT_TRUE(r.circles.empty());
  EXPECT_TRUE(hasWarning(r, "no circle"));
  EXPECT_EQ(r.edges.leftover_pixels, 1);
  EXPECT_EQ(r.edges.mapped_pixels, 1);
  EXPECT_FALSE(r.dirty.empty());
}

TEST(StrokeMapperBadInput, AllWhite) {
  StrokeResult s = makeThickStroke(kW, kH, 19);
  std::fill(s.footprint.values.begin(), s.footprint.values.end(), 1.0f);
  Volume v(glm::ivec3(64));
  MappingReport r = mapper().map(s, v);
  EXPECT_FALSE(r.circles.empty());
  EXPECT_FALSE(r.dirty.empty());
  // The top rows look above the horizon: their rays miss the canvas and say so.
  EXPECT_TRUE(hasWarning(r, "miss the canvas"));
  MappingReport rm = mapper().map(s, v, MappingMethod::kRayMarching);
  EXPECT_FALSE(rm.dirty.empty());
}

TEST(StrokeMapperBadInput, CanvasParallelToTheView) {
  StrokeResult s = makeThickStroke(kW, kH, 20);
  s.view.camera.eye = glm::vec3(3.0f, 0.0f, 0.0f);
  s.view.camera.target = glm::vec3(0.0f);
  s.canvas.altitude = 0.0f;
  Volume v(glm::ivec3(64));
  MappingReport r = mapper().map(s, v);
  EXPECT_TRUE(hasWarning(r, "parallel to the canvas"));
  {
    const std::vector<float> v_dense = v.toDense();
    for (size_t i = 0; i < v.voxelCount(); ++i) ASSERT_TRUE(std::isfinite(v_dense[i]));
  }
  MappingReport rm = mapper().map(s, v, MappingMethod::kRayMarching);
  (void)rm;
  {
    const std::vector<float> v_dense = v.toDense();
    for (size_t i = 0; i < v.voxelCount(); ++i) ASSERT_TRUE(std::isfinite(v_dense[i]));
  }
}

TEST(StrokeMapperBadInput, NaNValuesAreTreatedAsEmpty) {
  StrokeResult s = makeThickStroke(kW, kH, 21);
  s.footprint.values[0] = std::nanf("");
  Volume v(glm::ivec3(64));
  MappingReport r = mapper().map(s, v);
  EXPECT_TRUE(hasWarning(r, "NaN"));
  {
    const std::vector<float> v_dense = v.toDense();
    for (size_t i = 0; i < v.voxelCount(); ++i) ASSERT_TRUE(std::isfinite(v_dense[i]));
  }
}

}  // namespace
}  // namespace cb
