// A pen with only a tip (no pressure axis, pressure_max 0: eGalax, Nexio, IRTOUCH pens) paints:
// the painter gives its strokes the level −/+ set (0.6 at start), says so on the status line,
// and the journal keeps the device's pressure_raw 0 with the level used.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "drivers/core/journal.h"
#include "drivers/replay/replay_pen_source.h"
#include "tests/support/recorded_painter.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

TEST(TipOnlyPaint, APenWithoutPressurePaintsAtTheChosenLevel) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_tip_only_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  // The pen: the synthetic tablet without its pressure axis, one stroke, pressure 0 throughout.
  PenDeviceInfo tablet = syntheticTablet(kW, kH);
  tablet.pressure_max = 0;
  std::snprintf(tablet.name, sizeof tablet.name, "tip-only pen");
  const std::string pen_path = dir + "/pen.cbj";
  {
    JournalWriter journal;
    ASSERT_TRUE(journal.open(pen_path));
    const auto info = encodeDeviceInfo(tablet);
    journal.append(JournalRecordType::kDevice, 0, info.data(), info.size());
    int64_t t = 1'000'000'000;
    for (PenSample s :
         syntheticPenSamples(referencePaintStrokes(kW, kH)[0], tablet, kW, kH, 200.0, t)) {
      s.pressure_raw = 0;
      s.pressure = 0.0f;
      journal.appendPenSample(s);
    }
  }
  std::string error;
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}, dir + "/session.cbj", 0,
                           &error))
      << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  PaintLoopOptions options;
  options.max_frames = 400;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 2;
  replay_options.loop = true;  // stays connected, as a tablet does
  ReplayPenSource pen(pen_path, replay_options);
  PaintLoop loop(display, painter.renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  ASSERT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  painter.journal.close();
  if (const char* keep = std::getenv("CB_KEEP_FRAMES"))
    writePng(std::string(keep) + "/tip_only_pen.png",
             readFramebufferRgba8(display.framebuffer(), kW, kH));
  const std::string status = loop.screen().statusLine();
  EXPECT_NE(status.find("pen without pressure: strokes at 0.60 (-/+), erase: 4 or Menu"),
            std::string::npos)
      << status;
  EXPECT_GT(session.strokesMapped(), 0u);
  double density = 0;
  for (float d : session.volume().toDense()) density += d;
  EXPECT_GT(density, 0.0) << "the strokes of a pen without pressure made cloud";
  // The session journal holds what was painted: the level while the tip was down, the device's
  // own pressure_raw 0, and nothing while hovering.
  const JournalReadResult read = readJournal(painter.recorded);
  ASSERT_TRUE(read.error.empty()) << read.error;
  int down = 0;
  for (const JournalRecord& r : read.records) {
    if (r.type != JournalRecordType::kPenSample) continue;
    const std::optional<PenSample> s = decodePenSample(r.payload);
    ASSERT_TRUE(s);
    EXPECT_EQ(s->pressure_raw, 0);
    if (s->tipDown()) {
      EXPECT_FLOAT_EQ(s->pressure, 0.6f);
      ++down;
    } else {
      EXPECT_EQ(s->pressure, 0.0f);
    }
  }
  EXPECT_GT(down, 20);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
