// The kiosk's visitor screens in words: after a visitor painted and left, a countdown says when
// the sky clears and how to keep it; then the sky is cleared, the attract orbit resumes and an
// invitation asks passers-by to pick up the pen (EGL surfaceless, llvmpipe).
#include <gtest/gtest.h>

#include <filesystem>

#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/shell/paint_loop.h"
#include "app/shell/paint_screen.h"

#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 640, kH = 360;

TEST(KioskScreen, CountdownThenResetAndInvitation) {
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  ASSERT_TRUE(display) << error;
  VolumeRenderer renderer;
  ASSERT_TRUE(renderer.init(&error)) << error;
  PaintSession session({kW, kH, 64}, BrushConfig{}, MappingConfig{});
  // A visitor's cloud (a vacuum of a filled sky stands in for a stroke: any edit counts).
  Volume& v = session.volume();
  for (size_t i = 0; i < v.voxelCount(); ++i) v.data()[i] = 0.02f;
  v.markDirty(v.bounds());
  ASSERT_TRUE(session.apply(ui::VacuumCut{glm::vec3(0.0f), 0.5f}, 0, &error)) << error;
  PaintLoopOptions options;
  options.visitor_mode = true;
  options.idle_reset_s = 0.8;
  options.idle_warning_s = 0.6;
  options.max_frames = 100000;
  options.orbit_degrees_per_second = 0.0f;  // still until the reset (then no orbit to show)
  std::string countdown, invitation;
  ImageRgba8 countdown_frame, invitation_frame;
  bool reset_seen = false;
  PaintLoop* loop_ptr = nullptr;
  std::atomic<bool> stop{false};
  options.on_frame = [&](const PaintFrameInfo&) {
    const std::string& notice = loop_ptr->screen().notice();
    if (notice.rfind("Still there?", 0) == 0 && countdown.empty()) {
      countdown = notice;
      countdown_frame = readFramebufferRgba8(display->framebuffer(), kW, kH);
    }
    if (loop_ptr->screen().idleResets() > 0) reset_seen = true;
    if (reset_seen && notice.rfind("Pick up", 0) == 0 && invitation.empty()) {
      invitation = notice;
      invitation_frame = readFramebufferRgba8(display->framebuffer(), kW, kH);
      stop = true;
    }
  };
  PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
  loop_ptr = &loop;
  loop.attachPen(nullptr, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(&stop, &summary, &error)) << error;
  EXPECT_NE(countdown.find("The sky clears in"), std::string::npos) << countdown;
  EXPECT_NE(countdown.find("touch the pen"), std::string::npos);
  EXPECT_TRUE(reset_seen);
  EXPECT_EQ(invitation, "Pick up the pen and paint a cloud");
  double density = 0;
  for (size_t i = 0; i < v.voxelCount(); ++i) density += v.data()[i];
  EXPECT_EQ(density, 0.0) << "the idle reset cleared the sky";
  EXPECT_FALSE(session.history().canUndo() && density > 0);
  if (const char* keep = std::getenv("CB_KEEP_FRAMES")) {
    writePng(std::string(keep) + "/kiosk_countdown.png", countdown_frame);
    writePng(std::string(keep) + "/kiosk_invitation.png", invitation_frame);
  }
}

}  // namespace
}  // namespace cb
