// The surfaceless platform on real EGL (llvmpipe): opens, draws, reads back, presents.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/render/gl/display.h"

namespace cb {
namespace {

std::unique_ptr<Display> openSurfaceless(int w, int h) {
  DisplayOptions options;
  options.platform = DisplayPlatform::Surfaceless;
  options.width = w;
  options.height = h;
  std::string error;
  auto display = openDisplay(options, &error);
  EXPECT_NE(display, nullptr) << error;
  return display;
}

TEST(SurfacelessDisplay, OpensWithTheRequestedSizeAndGl45) {
  auto display = openSurfaceless(96, 40);
  ASSERT_NE(display, nullptr);
  EXPECT_STREQ(display->platformName(), "surfaceless");
  EXPECT_EQ(display->width(), 96);
  EXPECT_EQ(display->height(), 40);
  EXPECT_NE(display->framebuffer(), 0u);
  EXPECT_NE(display->context().version.find("4."), std::string::npos) << display->context().version;
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 45);
}

// Top half red, bottom half blue: checks both the drawing and the row order of readPixels.
TEST(SurfacelessDisplay, PresentsWhatWasDrawnTopRowFirst) {
  auto display = openSurfaceless(64, 48);
  ASSERT_NE(display, nullptr);
  std::string error;
  ASSERT_TRUE(display->makeCurrent(&error)) << error;
  glBindFramebuffer(GL_FRAMEBUFFER, display->framebuffer());
  glViewport(0, 0, 64, 48);
  glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 24, 64, 24);  // GL's y is up: the upper half
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  std::vector<uint8_t> rgba;
  ASSERT_TRUE(display->readPixels(&rgba));
  ASSERT_EQ(rgba.size(), 64u * 48u * 4u);
  auto pixel = [&](int x, int y) { return &rgba[(size_t(y) * 64 + size_t(x)) * 4]; };
  EXPECT_EQ(pixel(10, 2)[0], 255);
  EXPECT_EQ(pixel(10, 2)[2], 0);
  EXPECT_EQ(pixel(50, 45)[0], 0);
  EXPECT_EQ(pixel(50, 45)[2], 255);
  ASSERT_TRUE(display->present(&error)) << error;
  ASSERT_TRUE(display->present(&error)) << error;
  ASSERT_EQ(display->frameTimings().size(), 2u);
  const FrameTiming* last = display->frameTimings().last();
  EXPECT_EQ(last->frame, 2u);
  EXPECT_GE(last->shown_ns, last->submit_ns);
  EXPECT_FALSE(last->has_vblank);
  EXPECT_TRUE(display->pollEvents().empty());
}

TEST(SurfacelessDisplay, RejectsASizeOutOfRangeNamingIt) {
  DisplayOptions options;
  options.platform = DisplayPlatform::Surfaceless;
  options.width = 0;
  options.height = 100;
  std::string error;
  EXPECT_EQ(openDisplay(options, &error), nullptr);
  EXPECT_NE(error.find("0x100"), std::string::npos) << error;
}

// Injected key events come out of the next poll, in order, once.
TEST(SurfacelessDisplay, DeliversInjectedEventsOnceInOrder) {
  auto display = openSurfaceless(16, 16);
  ASSERT_NE(display, nullptr);
  EXPECT_TRUE(display->pollEvents().empty());
  for (uint32_t keysym : {uint32_t('s'), uint32_t('b'), uint32_t('q')})
    display->injectEvent(DisplayEvent::key(keysym, DisplayEvent::kCtrl));
  const std::vector<DisplayEvent> events = display->pollEvents();
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].keysym, uint32_t('s'));
  EXPECT_EQ(events[1].keysym, uint32_t('b'));
  EXPECT_EQ(events[2].keysym, uint32_t('q'));
  EXPECT_EQ(events[2].modifiers, uint32_t(DisplayEvent::kCtrl));
  EXPECT_TRUE(display->pollEvents().empty());
}

}  // namespace
}  // namespace cb
