#include "calibration/synthetic_stroke.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace cb {
namespace {

TEST(SyntheticStroke, SeededAndWithRequestedNoise) {
  StrokeSpec spec;
  spec.shape = StrokeShape::kCircle;
  spec.speed_mm_s = 300;
  spec.duration_s = 20;
  SyntheticStroke a = makeSyntheticStroke(spec), b = makeSyntheticStroke(spec);
  ASSERT_EQ(a.samples.size(), 4000u);
  double sum2 = 0, psum2 = 0;
  for (size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].x_mm, b.samples[i].x_mm);
    const double dx = a.samples[i].x_mm - a.samples[i].true_x_mm;
    sum2 += dx * dx;
    const double dp = a.samples[i].pressure - a.samples[i].true_pressure;
    psum2 += dp * dp;
  }
  EXPECT_NEAR(std::sqrt(sum2 / a.samples.size()), 0.05, 0.003);
  EXPECT_NEAR(std::sqrt(psum2 / a.samples.size()), 0.005, 0.0003);
  // Speed along the truth.
  const auto& s0 = a.samples[10];
  const auto& s1 = a.samples[11];
  EXPECT_NEAR(std::hypot(s1.true_x_mm - s0.true_x_mm, s1.true_y_mm - s0.true_y_mm) / 0.005, 300, 1);
}

TEST(SyntheticStroke, CsvRoundTripAndErrors) {
  StrokeSpec spec;
  spec.duration_s = 0.1;
  SyntheticStroke s = makeSyntheticStroke(spec);
  SyntheticStroke back;
  std::string err;
  ASSERT_TRUE(parseStrokeCsv(formatStrokeCsv(s), "x.csv", &back, &err)) << err;
  ASSERT_EQ(back.samples.size(), s.samples.size());
  EXPECT_NEAR(back.samples[3].x_mm, s.samples[3].x_mm, 1e-6);
  EXPECT_FALSE(parseStrokeCsv("t_ns,a\n0,1,2,3,4,5,6\n5,1,2,x,4,5,6\n", "bad.csv", &back, &err));
  EXPECT_NE(err.find("bad.csv:3: field 4"), std::string::npos) << err;
  EXPECT_FALSE(parseStrokeCsv("0,1,2,3,4,5,6\n0,1,2,3,4,5,6\n", "t.csv", &back, &err));
  EXPECT_NE(err.find("time does not increase"), std::string::npos);
}

TEST(SyntheticStroke, CommittedBenchStrokesMatchTheirSpecs) {
  // The CSVs under calibration/bench_strokes are generated from benchStrokeSpecs(); if a spec
  // changes, regenerate them (cloudbrush bench smoothing --write-strokes DIR).
  for (const StrokeSpec& spec : benchStrokeSpecs()) {
    const std::string path =
        std::string(CB_SOURCE_DIR) + "/calibration/bench_strokes/" + spec.name + ".csv";
    SyntheticStroke committed;
    std::string err;
    ASSERT_TRUE(readStrokeCsv(path, &committed, &err)) << err;
    SyntheticStroke fresh = makeSyntheticStroke(spec);
    ASSERT_EQ(committed.samples.size(), fresh.samples.size()) << spec.name;
    for (size_t i = 0; i < fresh.samples.size(); i += 17) {
      EXPECT_NEAR(committed.samples[i].x_mm, fresh.samples[i].x_mm, 1e-6) << spec.name << " " << i;
      EXPECT_NEAR(committed.samples[i].true_y_mm, fresh.samples[i].true_y_mm, 1e-6);
    }
  }
}

}  // namespace
}  // namespace cb
