#include "calibration/point_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include "tests/support/test_seed.h"

namespace cb {
namespace {

std::vector<glm::dvec2> grid(int nx, int ny, double w, double h) {
  std::vector<glm::dvec2> pts;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      pts.push_back({w * (0.05 + 0.9 * i / (nx - 1)), h * (0.05 + 0.9 * j / (ny - 1))});
  return pts;
}

glm::dmat3 rowMajor(std::initializer_list<double> v) {
  glm::dmat3 m;
  auto it = v.begin();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[c][r] = *it++;
  return m;
}

TEST(PointFit, HomographyRecoversSyntheticTransformsWithinHalfPixel) {
  // Source in px-like units over a 1920x1080 screen; several perspective transforms.
  const std::vector<glm::dmat3> truths = {
      rowMajor({1.02, 0.01, 5.0, -0.015, 0.98, -7.0, 1e-6, -2e-6, 1.0}),
      rowMajor({0.9, 0.2, 40.0, -0.1, 1.1, 12.0, 2e-5, 1e-5, 1.0}),
      rowMajor({1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0}),
  };
  std::mt19937_64 rng(test::testSeed("PointFit tap noise", 7));
  std::normal_distribution<double> noise(0.0, 0.15);  // tap noise in px
  for (const glm::dmat3& truth : truths) {
    const auto src = grid(3, 3, 1920, 1080);  // corners, edge midpoints, centre
    std::vector<glm::dvec2> dst;
    for (const auto& s : src)
      dst.push_back(applyTransform(truth, s) + glm::dvec2(noise(rng), noise(rng)));
    PointFitResult r = fitHomography(src, dst);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_LT(r.max_residual, 0.5);
    // The recovered map agrees with the truth over the whole screen, not only at the taps.
    for (const auto& p : grid(7, 5, 1920, 1080)) {
      EXPECT_LT(glm::length(applyTransform(r.transform, p) - applyTransform(truth, p)), 0.5);
    }
  }
}

TEST(PointFit, HomographyExactFromFourPoints) {
  const glm::dmat3 truth = rowMajor({1.1, 0.05, 30.0, 0.02, 0.95, -20.0, 3e-5, -1e-5, 1.0});
  const std::vector<glm::dvec2> src = {{0, 0}, {1000, 0}, {1000, 800}, {0, 800}};
  std::vector<glm::dvec2> dst;
  for (const auto& s : src) dst.push_back(applyTransform(truth, s));
  PointFitResult r = fitHomography(src, dst);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_LT(r.max_residual, 1e-6);
  EXPECT_NEAR(applyTransform(r.transform, {500, 400}).x, applyTransform(truth, {500, 400}).x, 1e-6);
}

TEST(PointFit, AffineRecoversRotationScaleShift) {
  const double a = 0.05;
  const glm::dmat3 truth = rowMajor(
      {1.01 * std::cos(a), -std::sin(a), 12.0, std::sin(a), 0.99 * std::cos(a), -3.0, 0, 0, 1});
  const auto src = grid(3, 3, 1280, 720);
  std::vector<glm::dvec2> dst;
  for (const auto& s : src) dst.push_back(applyTransform(truth, s));
  PointFitResult r = fitAffine(src, dst);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_LT(r.rms, 1e-6);
  EXPECT_EQ(r.residuals.size(), src.size());
}

TEST(PointFit, AffineCannotFollowPerspectiveAndSaysHowFar) {
  const glm::dmat3 truth = rowMajor({1, 0, 0, 0, 1, 0, 1e-4, 0, 1});
  const auto src = grid(3, 3, 1920, 1080);
  std::vector<glm::dvec2> dst;
  for (const auto& s : src) dst.push_back(applyTransform(truth, s));
  PointFitResult affine = fitAffine(src, dst);
  PointFitResult homography = fitHomography(src, dst);
  ASSERT_TRUE(affine.ok && homography.ok);
  EXPECT_GT(affine.max_residual, 5.0);
  EXPECT_LT(homography.max_residual, 1e-6);
}

TEST(PointFit, DegenerateLayoutsAreRejectedWithReason) {
  std::vector<glm::dvec2> line = {{0, 0}, {100, 100}, {200, 200}, {300, 300}, {400, 400}};
  PointFitResult h = fitHomography(line, line);
  EXPECT_FALSE(h.ok);
  EXPECT_NE(h.error.find("collinear"), std::string::npos) << h.error;
  PointFitResult a = fitAffine(line, line);
  EXPECT_FALSE(a.ok);
  EXPECT_NE(a.error.find("collinear"), std::string::npos) << a.error;
  PointFitResult few = fitHomography({{0, 0}, {1, 0}, {0, 1}}, {{0, 0}, {1, 0}, {0, 1}});
  EXPECT_FALSE(few.ok);
  EXPECT_NE(few.error.find("at least 4"), std::string::npos);
  PointFitResult mismatch = fitAffine({{0, 0}, {1, 0}, {0, 1}}, {{0, 0}});
  EXPECT_FALSE(mismatch.ok);
  PointFitResult nan = fitAffine({{0, 0}, {1, 0}, {0, NAN}}, {{0, 0}, {1, 0}, {0, 1}});
  EXPECT_FALSE(nan.ok);
  EXPECT_NE(nan.error.find("point 2"), std::string::npos);
}

TEST(PointFit, KindNamesRoundTrip) {
  for (PointFitKind k : {PointFitKind::kNone, PointFitKind::kAffine, PointFitKind::kHomography}) {
    PointFitKind back = PointFitKind::kNone;
    ASSERT_TRUE(parsePointFitKind(pointFitKindName(k), &back));
    EXPECT_EQ(back, k);
  }
  PointFitKind k;
  EXPECT_FALSE(parsePointFitKind("projective", &k));
}

}  // namespace
}  // namespace cb
