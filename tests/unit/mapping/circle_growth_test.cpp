#include "app/mapping/circle_growth.h"

#include <gtest/gtest.h>

#include "app/mapping/reference_strokes.h"
#include "app/mapping/stroke_random.h"

namespace cb {
namespace {

double coveredFraction(const Footprint& f, const CircleGrowthResult& r, float empty) {
  long long non_empty = 0, covered = 0;
  for (size_t i = 0; i < f.values.size(); ++i) {
    non_empty += f.values[i] > empty;
    covered += r.covered[i] && f.values[i] > empty;
  }
  return non_empty ? double(covered) / double(non_empty) : 0.0;
}

TEST(CircleRowSpan, AgreesWithThePerPixelPredicate) {
  StrokeRandom rng(1, 2);
  for (int k = 0; k < 200; ++k) {
    glm::vec2 c(float(rng.uniform() * 50.0), float(rng.uniform() * 50.0));
    int r = 1 + int(rng.uniform() * 20.0);
    for (int y = int(c.y) - r - 2; y <= int(c.y) + r + 2; ++y) {
      int x0 = 0, x1 = -1;
      bool any = circleRowSpan(c, r, y, &x0, &x1);
      for (int x = int(c.x) - r - 2; x <= int(c.x) + r + 2; ++x) {
        double dx = x - double(c.x), dy = y - double(c.y);
        bool inside = dx * dx + dy * dy <= double(r) * r;
        EXPECT_EQ(inside, any && x >= x0 && x <= x1) << "circle " << c.x << "," << c.y << " r" << r;
      }
    }
  }
}

// The Fig. 6.6-like stroke at the thesis's 1280×768 and initial diameter 128, with the thesis's
// Empty Test on the initial circle (the product tests the smallest circle, so that circles follow
// thin strokes; on this thick one that grows about 100 smaller circles instead of 15–40).
class ThickStroke : public ::testing::Test {
 protected:
  ThickStroke() { cfg.empty_test_on_smallest = false; }
  StrokeResult stroke = makeThickStroke(1280, 768, 6);
  CircleGrowthConfig cfg;
};

TEST_F(ThickStroke, FifteenToFortyCirclesCoverSeventyPercent) {
  CircleGrowthResult r = growCircles(stroke.footprint, stroke.path, cfg);
  EXPECT_GE(r.circles.size(), 15u);
  EXPECT_LE(r.circles.size(), 40u);
  EXPECT_GE(coveredFraction(stroke.footprint, r, cfg.empty_threshold), 0.70);
  EXPECT_GT(r.steps, 1);
}

TEST_F(ThickStroke, EveryAcceptedCircleIsEightyPercentWhiteInTheUnmaskedFootprint) {
  for (auto grow : {growCircles, growCirclesStraightforward}) {
    CircleGrowthResult r = grow(stroke.footprint, stroke.path, cfg);
    ASSERT_FALSE(r.circles.empty());
    for (const Circle& c : r.circles) {
      CircleCounts n = countCircle(stroke.footprint, nullptr, c.centre, c.radius, cfg);
      EXPECT_GE(n.whiteRatio(), cfg.accept_white_ratio)
          << "circle at " << c.centre.x << "," << c.centre.y << " r" << c.radius;
      EXPECT_LE(c.radius, cfg.initial_diameter_px / 2);
      EXPECT_GE(c.radius, cfg.min_radius_px);
    }
  }
}

TEST_F(ThickStroke, CoveredMaskIsExactlyTheUnionOfTheCircles) {
  CircleGrowthResult r = growCircles(stroke.footprint, stroke.path, cfg);
  const Footprint& f = stroke.footprint;
  std::vector<uint8_t> expected(f.values.size(), 0);
  for (const Circle& c : r.circles)
    for (int y = 0; y < f.height; ++y) {
      int x0, x1;
      if (!circleRowSpan(c.centre, c.radius, y, &x0, &x1)) continue;
      for (int x = std::max(0, x0); x <= std::min(f.width - 1, x1); ++x)
        expected[y * f.width + x] = 1;
    }
  EXPECT_EQ(expected, r.covered);
}

TEST_F(ThickStroke, FastAndStraightforwardVariantsFindSimilarCircles) {
  CircleGrowthResult fast = growCircles(stroke.footprint, stroke.path, cfg);
  CircleGrowthResult slow = growCirclesStraightforward(stroke.footprint, stroke.path, cfg);
  // Different radius searches, same rules: coverage within a few percent.
  EXPECT_NEAR(coveredFraction(stroke.footprint, fast, cfg.empty_threshold),
              coveredFraction(stroke.footprint, slow, cfg.empty_threshold), 0.05);
}

TEST(CircleGrowth, SmallerInitialDiameterGivesMoreCircles) {
  StrokeResult stroke = makeThickStroke(640, 384, 6);
  CircleGrowthConfig cfg;
  size_t previous = 0;
  for (int diameter : {128, 64, 32, 16}) {
    cfg.initial_diameter_px = diameter;
    CircleGrowthResult r = growCircles(stroke.footprint, stroke.path, cfg);
    EXPECT_GT(r.circles.size(), previous) << "diameter " << diameter;
    previous = r.circles.size();
  }
}

TEST(CircleGrowth, FirstCircleGrowsAtTheMiddleOfThePath) {
  Footprint f(200, 100);
  for (int y = 30; y < 70; ++y)
    for (int x = 10; x < 190; ++x) f.at(x, y) = 1.0f;
  std::vector<StrokePoint> path;
  for (int x = 20; x <= 180; x += 10) path.push_back({{float(x), 50.0f}, 1.0f, 0, 0, 0});
  CircleGrowthConfig cfg;
  cfg.initial_diameter_px = 32;
  CircleGrowthResult r = growCircles(f, path, cfg);
  ASSERT_FALSE(r.circles.empty());
  EXPECT_EQ(r.circles[0].centre, glm::vec2(path[path.size() / 2].footprint_px));
  EXPECT_EQ(r.circles[0].radius, 16);
  EXPECT_EQ(r.circles[0].step, 0);
}

TEST(CircleGrowth, EmptyAndTinyFootprintsGiveNoCircle) {
  CircleGrowthConfig cfg;
  Footprint empty(64, 64);
  EXPECT_TRUE(growCircles(empty, {}, cfg).circles.empty());
  Footprint dot(64, 64);
  dot.at(32, 32) = 1.0f;
  EXPECT_TRUE(growCircles(dot, {}, cfg).circles.empty());
  Footprint none;
  EXPECT_TRUE(growCircles(none, {}, cfg).circles.empty());
}

}  // namespace
}  // namespace cb
