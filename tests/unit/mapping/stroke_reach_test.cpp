// Where a stroke's mapping can write (app/mapping/stroke_reach.h), known before mapping: every
// voxel a real stroke writes — the product's brushes (config/brush.toml) and mapping
// (config/mapping.toml), the hybrid, ray-marching and sheet methods, from the default paint view
// panned and orbited — lies inside the reach the session grows the sky to hold.
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"
#include "app/brush/stroke_engine.h"
#include "app/brush/synthetic_strokes.h"
#include "app/core/config_paths.h"
#include "app/mapping/stroke_mapper.h"
#include "app/mapping/stroke_reach.h"
#include "app/scene/paint_camera.h"
#include "app/volume/sky_extent.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720;  // PaintSessionSettings' screen
constexpr int kGrid = 256;          // the painter's grid

StrokeResult paint(BrushKind kind, const Camera& camera, const SyntheticStroke& path) {
  StrokeEngine engine(loadDefaultBrushConfig(), kW, kH);
  engine.selectBrush(kind);
  engine.setPaintView(PaintView{camera}, Canvas{});
  engine.setNextStrokeIndex(7);
  std::vector<BrushInput> samples = sampleStroke(path, 200.0);
  engine.prepareNextStroke();
  engine.beginStroke(samples.front());
  for (size_t i = 1; i < samples.size(); ++i) engine.addSample(samples[i]);
  return engine.endStroke();
}

TEST(StrokeReach, EveryVoxelAStrokeWritesLiesInsideItsReach) {
  ASSERT_TRUE(std::filesystem::exists(configFile("mapping.toml")));
  StrokeMapper mapper(loadMappingConfig(configFile("mapping.toml")));
  mapper.setQuiet(true);
  const float aspect = float(kW) / float(kH);
  const glm::vec3 shift(3.0f, 0.0f, -2.0f);
  const Camera panned =
      defaultPaintCamera(Canvas{}, glm::vec3(-1.0f) + shift, glm::vec3(1.0f) + shift, aspect);
  // Looking straight down (a steep view: the canvas slab is seen face-on, so only the margin for
  // the spheres' widening keeps their rims inside the reach).
  Camera down = panned;
  down.eye = glm::vec3(shift.x, 2.5f, shift.z);
  down.target = glm::vec3(shift.x, 0.0f, shift.z - 0.01f);
  const Camera views[] = {panned, panned.orbited(70.0f), down};
  // A long curve, a straight ramp and a dab (a short firm touch: a few spheres as wide as the
  // inked rectangle, where the spheres' widening and edge scatter pass the inked pixels' rays).
  SyntheticStroke dab = pressureRamp(kW, kH);
  dab.control_points = {{0.5f * kW, 0.5f * kH}, {0.5f * kW + 12.0f, 0.5f * kH + 4.0f}};
  dab.pressure = [](float) { return 1.0f; };
  const SyntheticStroke paths[] = {gentleCurve(kW, kH), pressureRamp(kW, kH), dab};
  const SkyExtent widest{kGrid, kMaxSkySpan};
  int checked = 0;
  for (const Camera& camera : views)
    for (BrushKind kind : {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton})
      for (MappingMethod method :
           {MappingMethod::kHybrid, MappingMethod::kRayMarching, MappingMethod::kSheet}) {
        const SyntheticStroke& path = paths[checked % 3];
        const StrokeResult stroke = paint(kind, camera, path);
        Volume sky = makeSkyVolume(widest);
        const glm::vec3 voxel = sky.voxelSize();
        const SkyReach reach = strokeReach(stroke, mapper.config(), voxel.x);
        ASSERT_TRUE(reach.inked);
        ASSERT_TRUE(reach.bounded);
        mapper.map(stroke, sky, method);
        ASSERT_GT(sky.allocatedBricks(), 0u);
        glm::vec2 lo(1e9f), hi(-1e9f);
        for (const glm::ivec3& b : sky.allocatedBrickList()) {
          const VoxelBox box = sky.brickBox(b);
          for (int z = box.lo.z; z < box.hi.z; ++z)
            for (int y = box.lo.y; y < box.hi.y; ++y)
              for (int x = box.lo.x; x < box.hi.x; ++x) {
                if (sky.at(x, y, z) == 0.0f) continue;
                const glm::vec3 w = sky.voxelToWorld(glm::vec3(x, y, z) + 0.5f);
                lo = glm::min(lo, glm::vec2(w.x, w.z));
                hi = glm::max(hi, glm::vec2(w.x, w.z));
              }
        }
        const glm::vec2 half(0.5f * voxel.x, 0.5f * voxel.z);
        std::printf(
            "%-8s %-12s view %d: written x %.3f..%.3f z %.3f..%.3f; reach x %.3f..%.3f z "
            "%.3f..%.3f\n",
            brushKindName(kind), toString(method), checked / 9, double(lo.x), double(hi.x),
            double(lo.y), double(hi.y), double(reach.xz_min.x), double(reach.xz_max.x),
            double(reach.xz_min.y), double(reach.xz_max.y));
        EXPECT_GE(lo.x + half.x, reach.xz_min.x) << brushKindName(kind) << " " << toString(method);
        EXPECT_GE(lo.y + half.y, reach.xz_min.y) << brushKindName(kind) << " " << toString(method);
        EXPECT_LE(hi.x - half.x, reach.xz_max.x) << brushKindName(kind) << " " << toString(method);
        EXPECT_LE(hi.y - half.y, reach.xz_max.y) << brushKindName(kind) << " " << toString(method);
        // An over-estimate, not the whole sky: within 3/4 of a home box (1.5 world units) of
        // what was written on each side (the largest sphere twice over, at the far depth).
        EXPECT_LT(reach.xz_max.x - reach.xz_min.x, hi.x - lo.x + 3.0f);
        EXPECT_LT(reach.xz_max.y - reach.xz_min.y, hi.y - lo.y + 3.0f);
        ++checked;
      }
  EXPECT_EQ(checked, 27);
}

TEST(StrokeReach, AnEmptyFootprintReachesNothingAndARayMissingTheCanvasIsUnbounded) {
  const MappingConfig config;
  StrokeResult stroke;
  stroke.footprint = Footprint(64, 36);
  stroke.view.camera = defaultPaintCamera(Canvas{}, glm::vec3(-1.0f), glm::vec3(1.0f), 16.0f / 9);
  EXPECT_FALSE(strokeReach(stroke, config, 2.0f / 256).inked);
  stroke.footprint.at(32, 18) = 1.0f;
  const SkyReach centre = strokeReach(stroke, config, 2.0f / 256);
  EXPECT_TRUE(centre.inked && centre.bounded);
  // Looking level over the canvas: the top rows' rays pass above the horizon.
  stroke.view.camera.target = stroke.view.camera.eye + glm::vec3(0.0f, 0.0f, -1.0f);
  stroke.footprint.at(32, 0) = 1.0f;
  const SkyReach level = strokeReach(stroke, config, 2.0f / 256);
  EXPECT_TRUE(level.inked);
  EXPECT_FALSE(level.bounded);
}

}  // namespace
}  // namespace cb
