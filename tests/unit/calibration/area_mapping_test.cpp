#include "calibration/area_mapping.h"

#include <gtest/gtest.h>

#include "calibration/point_fit.h"

namespace cb {
namespace {

constexpr double kW = 200.0, kH = 100.0;  // tablet mm (2:1)

glm::dvec2 map(const AreaMapping& m, double x, double y) {
  return applyTransform(m.tablet_to_screen, {x, y});
}

void expectNear(glm::dvec2 a, glm::dvec2 b) {
  EXPECT_NEAR(a.x, b.x, 1e-9);
  EXPECT_NEAR(a.y, b.y, 1e-9);
}

TEST(AreaMapping, StretchMapsCornersToCorners) {
  AreaMappingConfig c;
  c.fit = AreaFit::kStretch;
  AreaMapping m = computeAreaMapping(c, kW, kH, 1280, 1024);
  ASSERT_TRUE(m.ok) << m.error;
  expectNear(map(m, 0, 0), {0, 0});
  expectNear(map(m, kW, kH), {1280, 1024});
  expectNear(map(m, kW, 0), {1280, 0});
}

TEST(AreaMapping, FitCropsTabletToScreenAspect) {
  AreaMappingConfig c;
  c.fit = AreaFit::kFit;
  // Square screen on a 2:1 tablet: the central 100x100 mm drive the whole screen.
  AreaMapping m = computeAreaMapping(c, kW, kH, 1000, 1000);
  ASSERT_TRUE(m.ok);
  expectNear(map(m, 50, 0), {0, 0});
  expectNear(map(m, 150, 100), {1000, 1000});
  // Equal scale in x and y: proportions kept.
  const glm::dvec2 d = map(m, 60, 10) - map(m, 50, 0);
  EXPECT_NEAR(d.x, d.y, 1e-9);
}

TEST(AreaMapping, LetterboxUsesWholeTabletInCentredRegion) {
  AreaMappingConfig c;
  c.fit = AreaFit::kLetterbox;
  AreaMapping m = computeAreaMapping(c, kW, kH, 1000, 1000);
  ASSERT_TRUE(m.ok);
  expectNear(map(m, 0, 0), {0, 250});
  expectNear(map(m, kW, kH), {1000, 750});
}

TEST(AreaMapping, QuarterTurnsSwapAxes) {
  AreaMappingConfig c;
  c.fit = AreaFit::kStretch;
  c.rotation_deg = 90;  // tablet turned clockwise: its top-left corner is now top-right
  AreaMapping m = computeAreaMapping(c, kW, kH, 1000, 2000);
  ASSERT_TRUE(m.ok);
  expectNear(map(m, 0, 0), {1000, 0});
  expectNear(map(m, kW, 0), {1000, 2000});
  expectNear(map(m, kW, kH), {0, 2000});
  c.rotation_deg = 180;
  m = computeAreaMapping(c, kW, kH, 1000, 500);
  expectNear(map(m, 0, 0), {1000, 500});
  c.rotation_deg = 270;
  m = computeAreaMapping(c, kW, kH, 1000, 2000);
  expectNear(map(m, 0, 0), {0, 2000});
}

TEST(AreaMapping, ArbitraryAngleKeepsWholeScreenReachableInsideTablet) {
  AreaMappingConfig c;
  c.fit = AreaFit::kFit;
  c.rotation_deg = 20;
  AreaMapping m = computeAreaMapping(c, kW, kH, 1600, 900);
  ASSERT_TRUE(m.ok);
  const glm::dmat3 inv = glm::inverse(m.tablet_to_screen);
  for (glm::dvec2 corner :
       {glm::dvec2(0, 0), glm::dvec2(1600, 0), glm::dvec2(0, 900), glm::dvec2(1600, 900)}) {
    const glm::dvec2 mm = applyTransform(inv, corner);
    EXPECT_GE(mm.x, -1e-9);
    EXPECT_LE(mm.x, kW + 1e-9);
    EXPECT_GE(mm.y, -1e-9);
    EXPECT_LE(mm.y, kH + 1e-9);
  }
  // The centre of the tablet is the centre of the screen.
  expectNear(map(m, kW / 2, kH / 2), {800, 450});
  // A pen stroke along the tablet's x axis appears turned by 20° clockwise on the screen.
  const glm::dvec2 d = map(m, kW / 2 + 10, kH / 2) - map(m, kW / 2, kH / 2);
  EXPECT_NEAR(std::atan2(d.y, d.x) * 180.0 / 3.14159265358979, 20.0, 1e-6);
}

TEST(AreaMapping, CustomAreaAndScreenRegion) {
  AreaMappingConfig c;
  c.fit = AreaFit::kStretch;
  c.tablet_area_mm = RectD{20, 10, 100, 50};
  c.screen_region_px = RectD{1920, 0, 1280, 720};  // second monitor
  AreaMapping m = computeAreaMapping(c, kW, kH, 3200, 1080);
  ASSERT_TRUE(m.ok);
  expectNear(map(m, 20, 10), {1920, 0});
  expectNear(map(m, 120, 60), {3200, 720});
}

TEST(AreaMapping, DisplayModeIgnoresCustomArea) {
  AreaMappingConfig c;
  c.fit = AreaFit::kDisplay;
  c.tablet_area_mm = RectD{20, 10, 100, 50};
  AreaMapping m = computeAreaMapping(c, kW, kH, 1920, 1080);
  ASSERT_TRUE(m.ok);
  expectNear(map(m, 0, 0), {0, 0});
  expectNear(map(m, kW, kH), {1920, 1080});
}

TEST(AreaMapping, BadInputNamesWhat) {
  AreaMappingConfig c;
  c.tablet_area_mm = RectD{150, 0, 100, 50};
  AreaMapping m = computeAreaMapping(c, kW, kH, 1920, 1080);
  EXPECT_FALSE(m.ok);
  EXPECT_NE(m.error.find("not inside the active area"), std::string::npos) << m.error;
  EXPECT_FALSE(computeAreaMapping({}, 0, kH, 1920, 1080).ok);
  EXPECT_FALSE(computeAreaMapping({}, kW, kH, 0, 1080).ok);
  AreaFit f;
  EXPECT_FALSE(parseAreaFit("zoom", &f));
  ASSERT_TRUE(parseAreaFit("letterbox", &f));
  EXPECT_EQ(f, AreaFit::kLetterbox);
}

}  // namespace
}  // namespace cb
