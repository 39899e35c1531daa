// The KMS display's refresh rate (session.json's refresh_hz, app/render/gl/display_kms_output.h)
// over real mode timings as monitors and TVs announce them: CEA-861 (CTA-861-G table 1: VIC 4,
// 5, 16, 31 and the 1000/1001 clock of 1080p59.94) and VESA DMT 1.0 rev. 13 (640x480@60,
// 1024x768@60), each as its drmModeModeInfo (clock in kHz, totals in pixels and lines, flags),
// against the rate the standard gives for it. Interlaced modes refresh at the field rate (the
// kernel's drm_mode_vrefresh), double-scan modes at half the line-pair rate.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "app/render/gl/display_kms_output.h"

namespace cb {
namespace {

drmModeModeInfo mode(const char* name, uint32_t clock_khz, uint16_t hdisplay, uint16_t hss,
                     uint16_t hse, uint16_t htotal, uint16_t vdisplay, uint16_t vss, uint16_t vse,
                     uint16_t vtotal, uint32_t flags, uint32_t vrefresh) {
  drmModeModeInfo m{};
  m.clock = clock_khz;
  m.hdisplay = hdisplay, m.hsync_start = hss, m.hsync_end = hse, m.htotal = htotal;
  m.vdisplay = vdisplay, m.vsync_start = vss, m.vsync_end = vse, m.vtotal = vtotal;
  m.flags = flags;
  m.vrefresh = vrefresh;
  std::strncpy(m.name, name, sizeof m.name - 1);
  return m;
}

struct Case {
  drmModeModeInfo mode;
  double hz;  // the standard's rate
};

TEST(KmsModeRefresh, RealModeTimingsGiveTheirStandardRates) {
  const uint32_t hv = DRM_MODE_FLAG_PHSYNC | DRM_MODE_FLAG_PVSYNC;
  const uint32_t nn = DRM_MODE_FLAG_NHSYNC | DRM_MODE_FLAG_NVSYNC;
  const Case cases[] = {
      // CEA VIC 16, 1920x1080p @ 60 Hz
      {mode("1920x1080", 148500, 1920, 2008, 2052, 2200, 1080, 1084, 1089, 1125, hv, 60), 60.0},
      // the same at the 1000/1001 clock (NTSC-derived 59.94 Hz)
      {mode("1920x1080", 148352, 1920, 2008, 2052, 2200, 1080, 1084, 1089, 1125, hv, 60),
       60.0 / 1.001},
      // CEA VIC 31, 1920x1080p @ 50 Hz
      {mode("1920x1080", 148500, 1920, 2448, 2492, 2640, 1080, 1084, 1089, 1125, hv, 50), 50.0},
      // CEA VIC 4, 1280x720p @ 60 Hz
      {mode("1280x720", 74250, 1280, 1390, 1430, 1650, 720, 725, 730, 750, hv, 60), 60.0},
      // CEA VIC 5, 1920x1080i @ 60 Hz: 30 frames, 60 fields a second
      {mode("1920x1080i", 74250, 1920, 2008, 2052, 2200, 1080, 1084, 1094, 1125,
            hv | DRM_MODE_FLAG_INTERLACE, 60),
       60.0},
      // DMT 640x480 @ 60 Hz: 25.175 MHz, 800 x 525
      {mode("640x480", 25175, 640, 656, 752, 800, 480, 490, 492, 525, nn, 60),
       25175000.0 / (800.0 * 525.0)},
      // DMT 1024x768 @ 60 Hz: 65 MHz, 1344 x 806
      {mode("1024x768", 65000, 1024, 1048, 1184, 1344, 768, 771, 777, 806, nn, 60),
       65000000.0 / (1344.0 * 806.0)},
      // a double-scanned 320x240 (each line shown twice): half the rate of its totals
      {mode("320x240", 12588, 320, 336, 384, 400, 240, 245, 246, 262, nn | DRM_MODE_FLAG_DBLSCAN,
            60),
       12588000.0 / (400.0 * 262.0) / 2.0},
  };
  for (const Case& c : cases) {
    std::string why;
    const std::optional<double> hz = kmsModeRefreshHz(c.mode, &why);
    ASSERT_TRUE(hz) << c.mode.name << ": " << why;
    // Within the rounding of the clock to whole kHz.
    EXPECT_NEAR(*hz, c.hz, c.hz * 0.5 / c.mode.clock)
        << c.mode.name << " at " << c.mode.clock << " kHz";
    // The kernel's integer vrefresh agrees when rounded.
    EXPECT_EQ(int(*hz + 0.5), int(c.mode.vrefresh)) << c.mode.name;
  }
  // 59.94 and 60 are told apart (the integer vrefresh cannot).
  EXPECT_LT(*kmsModeRefreshHz(cases[1].mode, nullptr), 59.95);
}

TEST(KmsModeRefresh, WithoutAClockTheModesVrefreshElseNothingAndWhy) {
  drmModeModeInfo m = mode("virtual", 0, 1024, 0, 0, 0, 768, 0, 0, 0, 0, 75);
  EXPECT_EQ(kmsModeRefreshHz(m, nullptr), std::optional<double>(75.0));
  m.vrefresh = 0;
  std::string why;
  EXPECT_FALSE(kmsModeRefreshHz(m, &why));
  EXPECT_NE(why.find("no timing"), std::string::npos) << why;
}

}  // namespace
}  // namespace cb
