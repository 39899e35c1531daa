// Golden images of painted strokes: three strokes of the stroke gallery (app/brush/
// stroke_gallery.h: the horizontal, the fast flick, the dot) painted at the product's defaults
// on the painter's 1920×1080 screen (config/brush.toml, config/mapping.toml, the starting
// paint view, the default sky; app/session/gallery_painting.h), rendered in the thesis style
// from the paint view at 320×180 (EGL surfaceless, llvmpipe) and compared with
// tests/golden/strokes/<name>.png: every channel of every pixel within kMaxPixelError and the
// mean within kMaxMeanError. They guard what a painted stroke looks like (size, continuity,
// billows) against regressions in the brushes and the mapping.
//
// Regenerate on purpose, review and commit:
//   CB_UPDATE_GOLDENS=1 ./build/tests/golden/strokes/stroke_golden_test
// On a mismatch the rendered image is written next to the test binary as <name>.actual.png.
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "app/core/config_paths.h"
#include "app/render/image_io.h"
#include "app/render/render_target.h"
#include "app/render/volume_renderer.h"
#include "app/session/gallery_painting.h"
#include "tests/support/golden_image.h"
#include "tests/unit/render/gl_test_context.h"

namespace cb {
namespace {

constexpr int kScreenW = 1920, kScreenH = 1080;  // painted on
constexpr int kW = 320, kH = 180;                // rendered at
// As tests/golden/render: llvmpipe's rounding differs by a few levels between machines.
constexpr int kMaxPixelError = 6;
constexpr double kMaxMeanError = 0.25;

std::string goldenPath(const std::string& name) {
  return std::string(CB_SOURCE_DIR) + "/tests/golden/strokes/" + name + ".png";
}

void expectMatchesGolden(const std::string& name, const GalleryCloud& cloud) {
  VolumeRenderer renderer;
  std::string err;
  ASSERT_TRUE(renderer.init(&err)) << err;
  renderer.sync(cloud.volume, Light{});
  RenderTarget target;
  ASSERT_TRUE(target.create(kW, kH, RenderTarget::Format::kRgba8, &err)) << err;
  renderer.render(cloud.camera, kW, kH, target.fbo(), RenderOptions{});
  test::expectImageMatchesGolden(goldenPath(name), name, target.readRgba8(), kMaxPixelError,
                                 kMaxMeanError);
}

TEST(StrokeGolden, GalleryStrokesAtProductDefaults) {
  CB_REQUIRE_GL();
  const BrushConfig brush = loadDefaultBrushConfig();
  StrokeMapper mapper(loadMappingConfig(configFile("mapping.toml")));
  mapper.setQuiet(true);
  const std::vector<GalleryStroke> gallery = strokeGallery(kScreenW, kScreenH);
  uint32_t index = 0;
  for (const GalleryStroke& g : gallery) {
    ++index;
    if (g.name != "horizontal" && g.name != "fast_flick" && g.name != "dot") continue;
    SCOPED_TRACE(g.name);
    const GalleryCloud cloud =
        paintGalleryStroke(g, brush.default_brush, brush, mapper, kScreenW, kScreenH, 100 + index);
    expectMatchesGolden("stroke_" + g.name, cloud);
  }
}

}  // namespace
}  // namespace cb
