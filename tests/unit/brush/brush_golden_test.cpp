// Golden footprints: fixed synthetic strokes (pressure ramp, tilt sweep, the eight strokes of 永)
// painted by each brush at 200 Hz with the built-in defaults, compared with committed 8-bit PGMs.
//
// Regenerate on purpose (after an intended change to a brush), then review the images:
//   CB_UPDATE_GOLDENS=1 build-brush/tests/unit/brush/brush_golden_test
// On a mismatch the actual footprint is written next to the test binary as actual_<name>.pgm.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"
#include "brush_test_support.h"

namespace cb::test {
namespace {

const std::string kGoldenDir = std::string(CB_SOURCE_DIR) + "/tests/unit/brush/golden/";

Footprint paintCase(BrushKind kind, const std::string& path_name) {
  BrushConfig config;  // built-in defaults: goldens do not move when config/brush.toml is tuned
  config.default_brush = kind;
  if (path_name == "yong") {
    const int size = 256;
    StrokeEngine engine(config, size, size);
    Footprint all(size, size);
    int64_t t = 0;
    for (const SyntheticStroke& s : yongStrokes(size)) {
      std::vector<BrushInput> samples = sampleStroke(s, 200.0, t);
      t = samples.back().t_ns + 200000000;
      combineMax(paintStroke(&engine, samples).footprint, &all);
    }
    return all;
  }
  const int w = 256, h = 128;
  StrokeEngine engine(config, w, h);
  SyntheticStroke s = path_name == "pressure_ramp" ? pressureRamp(w, h) : tiltSweep(w, h);
  return paintStroke(&engine, sampleStroke(s, 200.0)).footprint;
}

struct GoldenCase {
  BrushKind brush;
  const char* path;
};

class BrushGolden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(BrushGolden, MatchesCommittedFootprint) {
  const GoldenCase c = GetParam();
  const std::string name = std::string(brushKindName(c.brush)) + "_" + c.path;
  Footprint actual = paintCase(c.brush, c.path);
  ASSERT_GT(inkedPixels(actual), 100) << name << " painted almost nothing";
  std::string error;
  if (std::getenv("CB_UPDATE_GOLDENS")) {
    ASSERT_TRUE(writePgm(kGoldenDir + name + ".pgm", actual, &error)) << error;
    GTEST_SKIP() << "regenerated " << kGoldenDir << name << ".pgm";
  }
  Footprint golden;
  ASSERT_TRUE(readPgm(kGoldenDir + name + ".pgm", &golden, &error))
      << error << " (regenerate with CB_UPDATE_GOLDENS=1)";
  ASSERT_EQ(golden.width, actual.width);
  ASSERT_EQ(golden.height, actual.height);
  Footprint q = quantise8(actual);
  // Tolerance: a few 8-bit steps anywhere (float rounding on another compiler), and at most
  // 0.2 % of pixels further off than that.
  size_t off = 0;
  for (size_t i = 0; i < q.values.size(); ++i)
    off += std::abs(q.values[i] - golden.values[i]) > 3.5f / 255.0f;
  double mean = meanAbsDifference(q, golden);
  bool ok = mean < 0.5 / 255.0 && off <= q.values.size() / 500;
  if (!ok) writePgm("actual_" + name + ".pgm", actual, &error);
  EXPECT_LT(mean, 0.5 / 255.0) << name;
  EXPECT_LE(off, q.values.size() / 500) << name << ": pixels off by more than 3 levels";
}

INSTANTIATE_TEST_SUITE_P(
    AllBrushes, BrushGolden,
    ::testing::Values(GoldenCase{BrushKind::k2D, "pressure_ramp"},
                      GoldenCase{BrushKind::k2D, "tilt_sweep"}, GoldenCase{BrushKind::k2D, "yong"},
                      GoldenCase{BrushKind::k3D, "pressure_ramp"},
                      GoldenCase{BrushKind::k3D, "tilt_sweep"}, GoldenCase{BrushKind::k3D, "yong"},
                      GoldenCase{BrushKind::kSkeleton, "pressure_ramp"},
                      GoldenCase{BrushKind::kSkeleton, "tilt_sweep"},
                      GoldenCase{BrushKind::kSkeleton, "yong"}),
    [](const ::testing::TestParamInfo<GoldenCase>& info) {
      return std::string(brushKindName(info.param.brush)) + "_" + info.param.path;
    });

}  // namespace
}  // namespace cb::test
