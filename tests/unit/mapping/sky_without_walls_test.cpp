// A sky without walls: with the product's defaults — the default sky (SkyExtent: 1024
// × 256 × 1024 voxels for the painter's grid 256), config/brush.toml and config/mapping.toml, the
// real brushes, StrokeEngine, StrokeMapper and VolumeRenderer —
//   - a stroke drawn where the thesis's 256³ box ended (the paint view panned past its wall, as
//     the camera mode pans it) lands there and renders: the landed and IoU thresholds;
//   - a cloud at the far edge of the sky is lit and shadowed as the same cloud at the centre:
//     the sun is a direction, so the light volume and the rendered image move with the cloud;
//   - memory follows the painting: an empty sky holds ≤ 50 MB (volume bricks + the renderer's
//     GPU copies + its light volume, counted in bytes), the bundled cumulus and 100 strokes
//     spread across the sky ≤ 1 GB.
#include <algorithm>
#include <cstdio>
#include <deque>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"
#include "app/brush/stroke_engine.h"
#include "app/brush/synthetic_strokes.h"
#include "app/core/config_paths.h"
#include "app/mapping/stroke_mapper.h"
#include "app/render/volume_renderer.h"
#include "app/scene/paint_camera.h"
#include "app/volume/scene_generators.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume_paste.h"
#include "rendered_opacity.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720;  // PaintSessionSettings' screen
constexpr int kGrid = 256;          // the painter's grid (cloudbrush paint --grid)
const SkyExtent kSky{kGrid, kDefaultSkySpan};

class SkyWithoutWalls : public ::testing::Test {
 protected:
  void SetUp() override {
    CB_REQUIRE_GL();
    std::string err;
    ASSERT_TRUE(renderer.init(&err)) << err;
    ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
    ASSERT_TRUE(std::filesystem::exists(configFile("mapping.toml")));
    mapper = std::make_unique<StrokeMapper>(loadMappingConfig(configFile("mapping.toml")));
    mapper->setQuiet(true);
  }

  // The default paint view panned by `shift` (world units, on the canvas plane).
  static Camera pannedPaintCamera(glm::vec3 shift) {
    return defaultPaintCamera(Canvas{}, glm::vec3(-1.0f) + shift, glm::vec3(1.0f) + shift,
                              float(kW) / float(kH));
  }

  // The bytes the sky costs once the renderer has synced it: the volume's bricks, the GPU copies
  // and the light volume, each as counted by its owner.
  size_t syncedBytes(const Volume& sky) {
    renderer.sync(sky, Light{});
    return sky.memoryBytes() + renderer.memoryBytes() + renderer.lightVolume().memoryBytes();
  }

  StrokeResult paint(BrushKind kind, const Camera& camera, uint32_t stroke_index = 1) {
    StrokeEngine engine(loadDefaultBrushConfig(), kW, kH);
    engine.selectBrush(kind);
    engine.setPaintView(PaintView{camera}, Canvas{});
    engine.setNextStrokeIndex(stroke_index);
    std::vector<BrushInput> samples = sampleStroke(gentleCurve(kW, kH), 200.0);
    engine.prepareNextStroke();
    engine.beginStroke(samples.front());
    for (size_t i = 1; i < samples.size(); ++i) engine.addSample(samples[i]);
    return engine.endStroke();
  }

  std::deque<Volume> volumes;  // kept alive: the renderer knows a volume by its address
  VolumeRenderer renderer;
  RenderTarget target;
  std::unique_ptr<StrokeMapper> mapper;
};

TEST_F(SkyWithoutWalls, AStrokePastTheOldBoxsWallLandsAndRenders) {
  // The paint view moved 2.5 world units (320 voxels) along x and z, where panning and orbiting
  // take it: the drawable region lies wholly outside the
  // old box [-1,1]³, where the one-box sky dropped every voxel of a stroke.
  const Camera camera = pannedPaintCamera(glm::vec3(2.5f, 0.0f, 2.5f));
  for (BrushKind kind : {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton}) {
    const StrokeResult stroke = paint(kind, camera);
    Volume& sky = volumes.emplace_back(makeSkyVolume(kSky));
    mapper->map(stroke, sky);
    ASSERT_GT(sky.allocatedBricks(), 0u) << brushKindName(kind) << ": nothing landed";
    const glm::ivec3 old_box_hi = kSky.homeOffset() + glm::ivec3(kGrid);
    for (const glm::ivec3& b : sky.allocatedBrickList()) {
      const VoxelBox box = sky.brickBox(b);
      EXPECT_TRUE(box.lo.x >= old_box_hi.x - Volume::kBrickSize ||
                  box.lo.z >= old_box_hi.z - Volume::kBrickSize)
          << brushKindName(kind) << ": brick " << b.x << "," << b.y << "," << b.z
          << " inside the old box";
    }
    Volume one_box{glm::ivec3(kGrid)};  // the thesis's box: the same stroke is lost
    mapper->map(stroke, one_box);
    EXPECT_EQ(one_box.allocatedBricks(), 0u) << brushKindName(kind);

    const float empty = mapper->config().circles.empty_threshold;
    const std::vector<float> seen = test::renderedOpacity(renderer, target, sky, camera);
    long long ink = 0, landed = 0, either = 0;
    for (size_t i = 0; i < seen.size(); ++i) {
      const bool inked = stroke.footprint.values[i] > empty, shows = seen[i] > 0.5f;
      ink += inked;
      landed += inked && shows;
      either += inked || shows;
    }
    ASSERT_GT(ink, 5000) << brushKindName(kind);
    const double landed_fraction = double(landed) / double(ink);
    const double iou = double(landed) / double(either);
    std::printf("%-8s past the wall: %zu bricks, landed %.3f, IoU %.3f\n", brushKindName(kind),
                sky.allocatedBricks(), landed_fraction, iou);
    EXPECT_GE(landed_fraction, 0.95) << brushKindName(kind);  // the thresholds
    EXPECT_GE(iou, 0.85) << brushKindName(kind);
  }
}

// The same voxels moved by whole bricks from the centre to the far corner: the light volume at
// each voxel and every pixel of the image (the view moved with the cloud) are the same.
TEST_F(SkyWithoutWalls, ACloudAtTheFarEdgeIsLitAndShadowedAsAtTheCentre) {
  const Volume centre_cloud = placeInSky(makeBundledCumulus(glm::ivec3(kGrid), 1), kSky);
  const glm::ivec3 home = kSky.homeOffset();
  const glm::ivec3 corner(kSky.dims().x - kGrid, 0, kSky.dims().z - kGrid);  // touches the edge
  const glm::ivec3 move = corner - home;
  ASSERT_EQ(move % Volume::kBrickSize, glm::ivec3(0));
  Volume& edge = volumes.emplace_back(makeSkyVolume(kSky));
  pasteVolume(centre_cloud, {home, home + glm::ivec3(kGrid)}, move, &edge);
  Volume& centre = volumes.emplace_back(centre_cloud);

  const Light sun;  // the default sun
  const glm::vec3 world_move = glm::vec3(move) * centre.voxelSize();
  Camera view = Camera::reference();
  Camera moved_view = view;
  moved_view.eye += world_move;
  moved_view.target += world_move;

  RenderOptions options;
  renderer.sync(centre, sun);
  std::vector<float> light_at_centre;
  for (int y = 0; y < kGrid; y += 8)
    for (int x = 0; x < kGrid; x += 8)
      light_at_centre.push_back(renderer.lightVolume().at(home.x + x, y, home.z + kGrid / 2));
  renderer.render(view, kW, kH, target.fbo(), options);
  const ImageRgba8 at_centre = target.readRgba8();

  renderer.sync(edge, sun);
  size_t i = 0;
  float worst_light = 0.0f;
  for (int y = 0; y < kGrid; y += 8)
    for (int x = 0; x < kGrid; x += 8)
      worst_light = std::max(
          worst_light, std::abs(renderer.lightVolume().at(corner.x + x, y, corner.z + kGrid / 2) -
                                light_at_centre[i++]));
  renderer.render(moved_view, kW, kH, target.fbo(), options);
  const ImageRgba8 at_edge = target.readRgba8();

  int worst = 0;
  long long off_by_more_than_one = 0, cloud_pixels = 0, shadowed = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      int pixel = 0;
      for (int c = 0; c < 4; ++c)
        pixel = std::max(pixel, std::abs(int(at_centre.at(x, y)[c]) - int(at_edge.at(x, y)[c])));
      worst = std::max(worst, pixel);
      off_by_more_than_one += pixel > 1;
    }
  for (float t : light_at_centre) {
    cloud_pixels += 1;
    shadowed += t < 0.5f;
  }
  std::printf(
      "far edge vs centre: light differs by at most %.2g, pixels by %d/255 (%lld pixels "
      "by more than 1/255); %lld of %lld sampled light voxels in shadow\n",
      double(worst_light), worst, off_by_more_than_one, shadowed, cloud_pixels);
  EXPECT_GT(shadowed, 0) << "the cumulus casts no shadow on itself: the comparison is empty";
  EXPECT_LE(worst_light, 1e-6f);
  // The rays start from world positions 3 units apart, whose float rounding moves the samples
  // along them by a few ulps: a pixel here and there rounds 2/255 apart, never more.
  EXPECT_LE(worst, 2);
  EXPECT_LE(off_by_more_than_one, kW * kH / 10000);
}

TEST_F(SkyWithoutWalls, MemoryFollowsThePainting) {
  Volume& sky = volumes.emplace_back(makeSkyVolume(kSky));
  const size_t empty = syncedBytes(sky);
  std::printf("empty %dx%dx%d sky: %.1f MB (volume %.1f, GPU %.1f, light %.1f)\n", kSky.dims().x,
              kSky.dims().y, kSky.dims().z, empty / 1e6, sky.memoryBytes() / 1e6,
              renderer.memoryBytes() / 1e6, renderer.lightVolume().memoryBytes() / 1e6);
  EXPECT_LE(empty, size_t(50'000'000));

  // The bundled cumulus in the home box and 100 strokes of the 3D brush, one from each of 10 × 10
  // views spread across the sky.
  Volume& painted =
      volumes.emplace_back(placeInSky(makeBundledCumulus(glm::ivec3(kGrid), 1), kSky));
  uint32_t index = 1;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) {
      const glm::vec3 shift(-3.0f + 6.0f * float(i) / 9.0f, 0.0f, -3.0f + 6.0f * float(j) / 9.0f);
      mapper->map(paint(BrushKind::k3D, pannedPaintCamera(shift), index++), painted);
    }
  const size_t full = syncedBytes(painted);
  std::printf(
      "cumulus + 100 strokes across the sky: %.1f MB (volume %.1f in %zu bricks, GPU %.1f, "
      "light %.1f)\n",
      full / 1e6, painted.memoryBytes() / 1e6, painted.allocatedBricks(),
      renderer.memoryBytes() / 1e6, renderer.lightVolume().memoryBytes() / 1e6);
  EXPECT_GT(painted.allocatedBricks(), 2000u) << "the strokes did not spread across the sky";
  EXPECT_LE(full, size_t(1'000'000'000));
}

}  // namespace
}  // namespace cb
