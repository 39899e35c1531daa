// The stroke gallery (app/brush/stroke_gallery.h) painted at the product's defaults — the
// painter's 1920×1080 screen and starting paint view (defaultPaintCamera), the default canvas
// and 256-grid sky, config/brush.toml (its brush, at its brush size) and config/mapping.toml,
// through the real StrokeEngine and StrokeMapper — and what each stroke's cloud looks like,
// measured from the volume on the CPU (stroke_measures.h), in the paint view:
//   - continuity: no stretch of the drawn path farther than a quarter of the stroke's width
//     from the silhouette longer than 5 % of the width (a break in the cloud, not the nib's
//     centre line along a thin cloud's edge), and both ends inside it;
//   - billows: the silhouette's half-width varies along the stroke with a coefficient of
//     variation >= 0.15 (a constant-radius tube measures ~0.05; thesis §6.3–6.6: circles of
//     many sizes, spheres, edge puffs, noise);
//   - body: seen from the side, the cloud is at least 0.5 × as thick as it is wide;
//   - size: the mouse's stroke (fixed pressure 0.6) is 5–8 % of the screen height across.
// Every figure is printed. To measure what was there before (the checks stay the same, and
// fail): CB_GALLERY_LEGACY=1 paints with the values an old journal replays with (size 1, the
// skeleton stamped once per step, no billowing edge, no billowing mapping); CB_GALLERY_BRUSH_SIZE=S
// at brush size S; CB_GALLERY_DUMP_DIR=DIR writes each silhouette with its path as
// DIR/STROKE-BRUSH.png.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "app/brush/brush_config.h"
#include "app/brush/stroke_gallery.h"
#include "app/core/config_paths.h"
#include "app/mapping/stroke_mapper.h"
#include "app/render/image_io.h"
#include "app/session/gallery_painting.h"
#include "app/volume/sky_extent.h"
#include "stroke_measures.h"

namespace cb {
namespace {

constexpr int kW = 1920, kH = 1080;  // the painter's screen in the walk-through
constexpr int kDownscale = 2;        // silhouettes at 960×540: 2 screen px per pixel
// Acceptance thresholds (the figures).
constexpr double kMaxGap = 0.05, kMinCv = 0.15, kMinBody = 0.5;
constexpr double kMouseMinWidth = 0.05, kMouseMaxWidth = 0.08;  // of the screen height

struct Painted {
  test::PathMeasures path;
  double body = 0;
  double mapping_ms = 0;
};

// The silhouette (white = opaque) with the drawn path in red, for looking at a failure.
void writeSilhouette(const std::string& file, const test::Silhouette& s,
                     const std::vector<glm::vec2>& path) {
  ImageRgba8 image;
  image.width = s.width;
  image.height = s.height;
  image.pixels.resize(size_t(s.width) * s.height * 4, 255);
  for (size_t i = 0; i < s.opacity.size(); ++i)
    for (int c = 0; c < 3; ++c) image.pixels[i * 4 + c] = uint8_t(255.0f * s.opacity[i]);
  for (glm::vec2 p : path) {
    const int x = int(p.x) / s.downscale, y = int(p.y) / s.downscale;
    if (x >= 0 && y >= 0 && x < s.width && y < s.height) {
      uint8_t* px = image.at(x, y);
      px[0] = 255, px[1] = 0, px[2] = 0;
    }
  }
  writePng(file, image);
}

class StrokeGallery : public ::testing::Test {
 protected:
  void SetUp() override {
    config = loadDefaultBrushConfig();
    MappingConfig mapping = loadMappingConfig(configFile("mapping.toml"));
    const char* legacy = std::getenv("CB_GALLERY_LEGACY");
    if (legacy && std::string(legacy) == "1") {
      config.stroke.size = 1.0f;
      config.stroke.billow = 0.0f;
      config.skeleton.stamp_spacing_px = 0.0f;
      mapping.spheres.billow_amplitude = 0.0f;
    }
    if (const char* s = std::getenv("CB_GALLERY_BRUSH_SIZE")) config.stroke.size = std::stof(s);
    std::printf(
        "brush size %.2f, brush billow %.2f, mapping billow amplitude %.2f, skeleton stamp "
        "spacing %.2f\n",
        double(config.stroke.size), double(config.stroke.billow),
        double(mapping.spheres.billow_amplitude), double(config.skeleton.stamp_spacing_px));
    mapper = std::make_unique<StrokeMapper>(mapping);
    mapper->setQuiet(true);
  }

  Painted paint(const GalleryStroke& g, BrushKind kind, uint32_t index) {
    const GalleryCloud cloud = paintGalleryStroke(g, kind, config, *mapper, kW, kH, index);
    const Volume& volume = cloud.volume;
    const MappingReport& report = cloud.report;
    Painted p;
    p.mapping_ms = cloud.mapping_ms;
    std::vector<glm::vec2> path;
    glm::vec2 lo(1e9f), hi(-1e9f);
    for (const BrushInput& in : g.samples) {
      path.push_back(in.footprint_px);
      lo = glm::min(lo, in.footprint_px);
      hi = glm::max(hi, in.footprint_px);
    }
    const float margin = 0.3f * kH;
    const glm::ivec4 rect(glm::ivec2(lo - margin), glm::ivec2(hi + margin));
    const test::Silhouette s =
        test::silhouetteOpacity(volume, report.dirty, cloud.camera, kW, kH, kDownscale, rect);
    p.path = test::measureAlongPath(s, path, g.point_like);
    if (const char* dir = std::getenv("CB_GALLERY_DUMP_DIR"))
      writeSilhouette(std::string(dir) + "/" + g.name + "-" + brushKindName(kind) + ".png", s,
                      path);
    p.body = test::bodyRatio(volume, cloud.camera, cloud.canvas, kW, kH, path, g.point_like);
    std::printf(
        "%-12s %-8s width %5.1f px = %5.2f %% of height | cv %.3f | widest gap %.3f "
        "width, ends %s (short by %.3f width) | body %.2f | mapping %.0f ms\n",
        g.name.c_str(), brushKindName(kind), p.path.width_px, 100.0 * p.path.width_px / kH,
        p.path.cv, p.path.widest_gap, p.path.ends_inside > 0 ? "in" : "OUT", p.path.end_shortfall,
        p.body, p.mapping_ms);
    std::fflush(stdout);
    return p;
  }

  BrushConfig config;
  std::unique_ptr<StrokeMapper> mapper;
};

TEST_F(StrokeGallery, EveryStrokeIsAContinuousBillowingBody) {
  const std::vector<GalleryStroke> gallery = strokeGallery(kW, kH);
  ASSERT_EQ(gallery.size(), 12u);
  uint32_t index = 0;
  for (const GalleryStroke& g : gallery) {
    const Painted p = paint(g, config.default_brush, 100 + index++);
    EXPECT_LE(p.path.widest_gap, kMaxGap) << g.name << ": the cloud breaks along the path";
    EXPECT_EQ(p.path.ends_inside, 1.0) << g.name << ": an end of the stroke has no cloud";
    // Billows are variation along a stroke: a dot's or a dab's outline radius is printed, not
    // checked. A scribble's path runs through its own cloud (its legs merge), so the walk across
    // the path measures the whole tangle, not a cross-section: its body is printed, not checked.
    if (!g.point_like) {
      EXPECT_GE(p.path.cv, kMinCv) << g.name << ": a tube, not billows";
    }
    if (g.name != "scribble") {
      EXPECT_GE(p.body, kMinBody) << g.name << ": flat from the side";
    }
    if (g.name == "mouse") {
      EXPECT_GE(p.path.width_px / kH, kMouseMinWidth) << "the mouse's stroke is a thin line";
      EXPECT_LE(p.path.width_px / kH, kMouseMaxWidth) << "the mouse's stroke is a blob";
    }
  }
}

// The 2D brush resamples its path as the 3D brush does: a fast flick and a straight line are
// one body. So is the skeleton brush's, whose bristles trail the rod (thesis §5.2: they lean one
// way and drag behind the pen): its ink may stop short of the pen's end by the trailing
// bristles' lean, so its widest gap is held to kSkeletonMaxGap of the width, not kMaxGap. Its
// ends may fall outside the cloud by that lean too: the spine rests 12° off plumb and trails
// away from the pen's tilt (skeleton_brush.cpp), so the ink sits up to a third of a width
// behind the pen (horizontal: 0.33, flick 0.06, mouse 0.02 measured); an end that the brush
// never reached (a stroke cut short, a lost last stamp) is a width or more away.
TEST_F(StrokeGallery, TheTwoDAndSkeletonBrushesLeaveContinuousStrokes) {
  constexpr double kSkeletonMaxGap = 0.25;
  constexpr double kSkeletonMaxEndShortfall = 0.5;
  uint32_t index = 200;
  for (const GalleryStroke& g : strokeGallery(kW, kH)) {
    if (g.name != "horizontal" && g.name != "fast_flick" && g.name != "mouse") continue;
    const Painted p = paint(g, BrushKind::k2D, index++);
    EXPECT_LE(p.path.widest_gap, kMaxGap) << g.name;
    EXPECT_EQ(p.path.ends_inside, 1.0) << g.name;
    const Painted skeleton = paint(g, BrushKind::kSkeleton, index++);
    EXPECT_LE(skeleton.path.widest_gap, kSkeletonMaxGap) << g.name << " (skeleton)";
    EXPECT_LE(skeleton.path.end_shortfall, kSkeletonMaxEndShortfall)
        << g.name << " (skeleton): the ink stops short of the pen's end";
  }
}

}  // namespace
}  // namespace cb
