// The platform flag and the automatic choice, on this machine's real EGL (llvmpipe).
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "app/render/gl/display.h"

namespace cb {
namespace {

TEST(DisplayChoice, ParsesEveryPlatformNameAndRejectsOthers) {
  for (DisplayPlatform p : {DisplayPlatform::Auto, DisplayPlatform::Kms, DisplayPlatform::X11,
                            DisplayPlatform::Surfaceless}) {
    DisplayPlatform parsed = DisplayPlatform::Auto;
    ASSERT_TRUE(parseDisplayPlatform(displayPlatformName(p), &parsed));
    EXPECT_EQ(parsed, p);
  }
  DisplayPlatform parsed = DisplayPlatform::Kms;
  EXPECT_FALSE(parseDisplayPlatform("wayland", &parsed));
  EXPECT_FALSE(parseDisplayPlatform("", &parsed));
  EXPECT_EQ(parsed, DisplayPlatform::Kms);
}

TEST(DisplayChoice, KmsOnAMissingCardNamesTheCard) {
  DisplayOptions options;
  options.platform = DisplayPlatform::Kms;
  options.drm_device = "/nonexistent/dri/card7";
  std::string error;
  EXPECT_EQ(openDisplay(options, &error), nullptr);
  EXPECT_NE(error.find("/nonexistent/dri/card7"), std::string::npos) << error;
}

TEST(DisplayChoice, KmsOnANonDrmFileSaysSo) {
  DisplayOptions options;
  options.platform = DisplayPlatform::Kms;
  options.drm_device = "/dev/null";
  std::string error;
  EXPECT_EQ(openDisplay(options, &error), nullptr);
  EXPECT_NE(error.find("/dev/null"), std::string::npos) << error;
}

TEST(DisplayChoice, X11OnAnUnreachableServerNamesIt) {
  DisplayOptions options;
  options.platform = DisplayPlatform::X11;
  options.x11_display = ":4093";  // nothing listens there
  std::string error;
  EXPECT_EQ(openDisplay(options, &error), nullptr);
  EXPECT_NE(error.find(":4093"), std::string::npos) << error;
}

// With no DISPLAY and no card we are master of, auto falls through to surfaceless and says why.
TEST(DisplayChoice, AutoWithoutScreenIsSurfacelessAndExplainsWhy) {
  unsetenv("DISPLAY");
  DisplayOptions options;
  options.drm_device = "/nonexistent/dri/card0";
  options.width = 32;
  options.height = 16;
  std::string error, note;
  auto display = openDisplay(options, &error, &note);
  ASSERT_NE(display, nullptr) << error;
  EXPECT_STREQ(display->platformName(), "surfaceless");
  EXPECT_EQ(display->width(), 32);
  EXPECT_EQ(display->height(), 16);
  EXPECT_NE(note.find("DISPLAY is not set"), std::string::npos) << note;
  EXPECT_NE(note.find("/nonexistent/dri/card0"), std::string::npos) << note;
}

}  // namespace
}  // namespace cb
