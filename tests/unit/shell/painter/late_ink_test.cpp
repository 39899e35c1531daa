// The late ink (PaintLoopOptions::late_ink): the samples latched at the end of a frame are drawn
// over the made frame in the box they changed (the scene and ink composited again, the heads-up
// items and the UI drawn over them again there). Each such frame must be, pixel for pixel, the
// frame the whole path draws when it is given the same samples before the frame — mid-stroke,
// and the lit cloud after the stroke. Tolerance 0: the same shaders draw the same pixels, only
// fewer of them.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "app/render/hud_overlay.h"
#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/ui_overlay.h"
#include "drivers/core/pen_source.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 640, kH = 360, kGrid = 64;

// A tablet that hands over one sample per poll, so which samples a frame shows depends only on
// how often the loop polls (the frame's start, after the scene, and with late ink at its end).
class OnePerPoll final : public PenSource {
 public:
  explicit OnePerPoll(std::vector<PenSample> samples)
      : samples_(std::move(samples)), info_(syntheticTablet(kW, kH)) {}
  const char* backendName() const override { return "one-per-poll"; }
  void poll(int, std::vector<PenSample>& out) override {
    if (taken_ < samples_.size()) out.push_back(samples_[taken_++]);
  }
  PenConnection connection() const override { return PenConnection::kConnected; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override { return "one sample per poll"; }
  size_t taken() const { return taken_; }
  bool done() const { return taken_ == samples_.size(); }

 private:
  std::vector<PenSample> samples_;
  size_t taken_ = 0;
  PenDeviceInfo info_;
};

struct Painted {
  std::map<size_t, ImageRgba8> by_samples;  // a mid-stroke frame, by the samples it shows
  std::map<size_t, bool> late_ink;          // whether that frame's late ink drew anything
  ImageRgba8 settled;                       // the last frame, the stroke's cloud at full resolution
  long late_frames = 0;
};

Painted paint(bool late_ink) {
  Painted run;
  const std::string dir = (std::filesystem::temp_directory_path() /
                           ("cb_late_ink_" + std::to_string(::getpid()) + (late_ink ? "_l" : "_w")))
                              .string();
  std::filesystem::create_directories(dir + "/state");
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  EXPECT_TRUE(display) << error;
  if (!display) return run;
  VolumeRenderer renderer;
  EXPECT_TRUE(renderer.init(&error)) << error;
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  // Stamped at 1 s of the pen's clock: more than a minute before the loop's now, so the painter
  // never repeats a resting sample on its own (PaintScreen::repeatRestingPen).
  OnePerPoll pen(syntheticPenSamples(referencePaintStrokes(kW, kH)[0], syntheticTablet(kW, kH), kW,
                                     kH, 200.0, 1'000'000'000));
  std::atomic<bool> stop{false};
  int after_refined = -1;  // frames since the stroke's cloud was shown at full resolution
  PaintLoopOptions options;
  options.max_seconds = 100.0;  // a bound for a stuck loop
  options.late_ink = late_ink;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  options.on_frame = [&](const PaintFrameInfo& info) {
    const bool drew_late = info.late_ink && info.late_box[2] > info.late_box[0];
    run.late_frames += drew_late;
    if (info.in_stroke && !pen.done()) {
      run.by_samples[pen.taken()] = readFramebufferRgba8(display->framebuffer(), kW, kH);
      run.late_ink[pen.taken()] = drew_late;
    }
    if (info.refined_after_lift) after_refined = 0;
    if (after_refined >= 0 && ++after_refined == 3) {
      run.settled = readFramebufferRgba8(display->framebuffer(), kW, kH);
      stop = true;
    }
  };
  PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  EXPECT_TRUE(loop.run(&stop, &summary, &error)) << error;
  EXPECT_EQ(summary.quit_reason, "signal") << "the stroke's cloud was refined and settled";
  EXPECT_EQ(session.strokesMapped(), 1u);
  std::filesystem::remove_all(dir);
  return run;
}

size_t differingPixels(const ImageRgba8& a, const ImageRgba8& b) {
  size_t n = 0;
  for (size_t i = 0; i + 3 < a.pixels.size() && i + 3 < b.pixels.size(); i += 4)
    n += a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] ||
         a.pixels[i + 2] != b.pixels[i + 2] || a.pixels[i + 3] != b.pixels[i + 3];
  return n;
}

TEST(LateInk, TheLateLatchedFrameIsTheWholePathsFramePixelForPixel) {
  const Painted late = paint(true);
  const Painted whole = paint(false);
  EXPECT_GT(late.late_frames, 10) << "the late ink drew samples latched at the frames' end";
  EXPECT_EQ(whole.late_frames, 0);
  size_t compared = 0;
  const ImageRgba8* first = nullptr;
  const ImageRgba8* last = nullptr;
  for (const auto& [samples, image] : late.by_samples) {
    const auto other = whole.by_samples.find(samples);
    if (other == whole.by_samples.end() || !late.late_ink.at(samples)) continue;
    ASSERT_EQ(image.pixels.size(), size_t(kW) * kH * 4);
    EXPECT_EQ(differingPixels(image, other->second), 0u)
        << "the frame showing the first " << samples << " samples";
    ++compared;
    if (!first) first = &image;
    last = &image;
  }
  EXPECT_GE(compared, 5u) << "frames with late ink that the whole path also drew";
  ASSERT_TRUE(first && last);
  EXPECT_GT(differingPixels(*first, *last), 100u) << "the compared frames show the ink growing";
  // CB_LATE_INK_SHOTS=DIR keeps the last compared pair and the settled frame as PNGs (to look at).
  if (const char* shots = std::getenv("CB_LATE_INK_SHOTS")) {
    writePng(std::string(shots) + "/late_ink_mid_stroke.png", *last);
    for (const auto& [samples, image] : late.by_samples)
      if (&image == last)
        writePng(std::string(shots) + "/whole_path_mid_stroke.png", whole.by_samples.at(samples));
    writePng(std::string(shots) + "/late_ink_settled.png", late.settled);
  }
  ASSERT_EQ(late.settled.pixels.size(), size_t(kW) * kH * 4);
  EXPECT_EQ(differingPixels(late.settled, whole.settled), 0u) << "the lit cloud after the stroke";
}

// The frame under the overlays: a colour per pixel, so a box drawn again over the wrong pixels
// shows.
void drawGround(GLuint fbo, const glm::ivec4* box) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glViewport(0, 0, kW, kH);
  if (box) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(box->x, kH - box->w, box->z - box->x, box->w - box->y);
  }
  glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
}

// The HUD and the UI drawn again only in a box, over the ground put back there, leave the frame
// as the whole draw made it — inside the box (nothing missed) and outside (nothing blended
// twice) — for boxes on text, on the status bar's edge and on half-transparent items.
TEST(LateInk, TheHudAndUiDrawnAgainInABoxLeaveTheWholeDrawsPixels) {
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  const GLuint fbo = display->framebuffer();
  HudOverlay hud;
  ASSERT_TRUE(hud.init(&error)) << error;
  const std::vector<HudItem> items = {
      makeHudRect(0.0f, 0.0f, 200.5f, 360.0f, {0.0f, 0.0f, 0.0f, 0.45f}),  // a veil
      makeHudSegment({10.3f, 20.7f}, {600.2f, 300.9f}, 2.0f, {1.0f, 1.0f, 1.0f, 0.5f}),
      makeHudRing({320.0f, 180.0f}, 40.0f, 3.0f, {1.0f, 0.55f, 0.2f, 0.9f})};
  UiOverlay ui;
  ASSERT_TRUE(ui.init(&error)) << error;
  UiOverlayState state;
  state.status = "Paint 画 · brush 3 · size 24 · pen";
  state.toast = "Saved 已保存";
  state.hint = {"Press the pen to paint", "用笔按下来画"};
  drawGround(fbo, nullptr);
  hud.draw(fbo, kW, kH, items);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  ui.draw(kW, kH, 1.0 / 60.0, state);
  const ImageRgba8 whole = readFramebufferRgba8(fbo, kW, kH);
  const glm::ivec4 boxes[] = {{37, 3, 301, 61}, {150, 40, 420, 330}, {0, 0, kW, kH}, {5, 5, 6, 6}};
  for (const glm::ivec4& box : boxes) {
    drawGround(fbo, &box);
    hud.draw(fbo, kW, kH, items, &box);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, kW, kH);
    ASSERT_TRUE(ui.redraw(box));
    EXPECT_EQ(differingPixels(readFramebufferRgba8(fbo, kW, kH), whole), 0u)
        << "box " << box.x << "," << box.y << " - " << box.z << "," << box.w;
  }
  // It can fail: the ground put back without the overlays differs from the whole frame.
  const glm::ivec4 box = boxes[0];
  drawGround(fbo, &box);
  EXPECT_GT(differingPixels(readFramebufferRgba8(fbo, kW, kH), whole), 1000u);
}

}  // namespace
}  // namespace cb
