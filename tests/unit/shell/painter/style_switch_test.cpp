// The first frame the painter presents after the style command (T) shows the next
// style. The bundled cumulus is opened (Ctrl+O), a few frames settle at full resolution in the
// thesis style, T is pressed, and the very next frame drawn must differ from the settled thesis
// frame, while what is on screen well after it (nothing changed since) equals that first frame.
#include <gtest/gtest.h>

#include <xkbcommon/xkbcommon-keysyms.h>

#include <cstdlib>
#include <filesystem>

#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "app/volume/scene_generators.h"
#include "app/volume/volume_file.h"
#include "drivers/core/clock.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

// Mean absolute difference per channel over the frame, in 1/255 units.
double meanDifference(const ImageRgba8& a, const ImageRgba8& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
  return sum / double(a.pixels.size());
}

TEST(StyleSwitch, TheFirstFrameAfterTShowsTheNextStyle) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_style_switch_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  saveVolume(makeBundledCumulus(glm::ivec3(kGrid), 1), dir + "/state/source.vol");
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});

  PaintLoopOptions options;
  options.max_frames = 400;
  options.orbit_degrees_per_second = 0.0f;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ASSERT_TRUE(parseKeyList("ctrl+o", &options.initial_keys, &error)) << error;
  // The loop draws only when something changed; each_iteration runs every tick, drawn or not.
  ImageRgba8 settled, after_t, after_that;
  std::string style_at_t;
  long ticks = 0, draws_after_t = 0;
  bool t_pressed = false;
  options.on_frame = [&](const PaintFrameInfo&) {
    if (t_pressed && ++draws_after_t == 1)
      after_t = readFramebufferRgba8(display->framebuffer(), kW, kH);
  };
  // Messages time out on the test's own clock (a tick a 60th of a second), not the machine's
  // speed: on a loaded machine 60 ticks outlasted the "Opened" message, which then vanished
  // between the two frames compared.
  ManualClock clock(1'000'000'000);
  options.clock = &clock;
  options.each_iteration = [&](bool) {
    ++ticks;
    clock.advance(16'666'667);
    if (ticks == 60) {  // the opened cloud, refined to full resolution long ago
      settled = readFramebufferRgba8(display->framebuffer(), kW, kH);
      style_at_t = session.styleName();
      t_pressed = true;
      display->injectEvent(DisplayEvent::key('t'));
    } else if (ticks == 120) {
      after_that = readFramebufferRgba8(display->framebuffer(), kW, kH);
      display->injectEvent(DisplayEvent::key(XKB_KEY_Escape));
    }
  };
  PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
  loop.attachPen(nullptr, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  ASSERT_GE(ticks, 120) << "quit: " << summary.quit_reason;
  ASSERT_GE(draws_after_t, 1) << "nothing was drawn after T";
  if (const char* keep = std::getenv("CB_KEEP_FRAMES")) {
    writePng(std::string(keep) + "/style_switch_thesis.png", settled);
    writePng(std::string(keep) + "/style_switch_first_after_t.png", after_t);
    writePng(std::string(keep) + "/style_switch_later.png", after_that);
  }
  EXPECT_EQ(style_at_t, "thesis");
  EXPECT_EQ(session.styleName(), "physical");
  const double changed = meanDifference(settled, after_t);
  const double later = meanDifference(after_t, after_that);
  std::printf(
      "mean |Δ| thesis -> first frame after T %.2f/255; what is shown 60 ticks later %.2f\n",
      changed, later);
  EXPECT_GT(changed, 2.0) << "the first frame after T still shows the thesis style";
  EXPECT_LT(later, 0.5) << "the new style arrived only in a later frame";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
