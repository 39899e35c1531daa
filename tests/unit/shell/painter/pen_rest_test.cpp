// A pen resting still on the tablet sends nothing (evdev reports changes only); the painter
// repeats its last sample while the tip is down, so the open stroke still ends by itself after
// the rest time (thesis §7.7.5, problem 3; PaintSession's auto_end_still_ms, 2 s), as it does
// for the mouse held still.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/session/paint_session.h"
#include "app/session/synthetic_session.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "drivers/core/clock.h"
#include "drivers/core/pen_source.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

// A tablet that delivers one stroke with its tip left down, then nothing: a pen at rest.
class RestingPen final : public PenSource {
 public:
  explicit RestingPen(std::vector<PenSample> samples)
      : samples_(std::move(samples)), info_(syntheticTablet(kW, kH)) {}
  const char* backendName() const override { return "resting"; }
  void poll(int, std::vector<PenSample>& out) override {
    out.insert(out.end(), samples_.begin(), samples_.end());
    samples_.clear();
  }
  PenConnection connection() const override { return PenConnection::kConnected; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override { return "resting pen"; }

 private:
  std::vector<PenSample> samples_;
  PenDeviceInfo info_;
};

// The first reference stroke up to its last sample with the tip down, that sample 0.1 s ago.
std::vector<PenSample> strokeLeftDown() {
  std::vector<PenSample> samples = syntheticPenSamples(referencePaintStrokes(kW, kH)[0],
                                                       syntheticTablet(kW, kH), kW, kH, 200.0, 0);
  while (!samples.empty() && !(samples.back().buttons & kPenTip)) samples.pop_back();
  const int64_t shift = MonotonicClock().nowNs() - 100'000'000 - samples.back().t_ns;
  for (PenSample& s : samples) s.t_ns += shift;
  return samples;
}

// Runs the painter for `seconds` after a stroke whose tip stays down and whose pen then sends
// nothing; returns the strokes mapped.
size_t strokesAfterRest(double seconds) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_pen_rest_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  std::string error;
  std::unique_ptr<Display> display = test::openTestDisplay(kW, kH, &error);
  EXPECT_TRUE(display) << error;
  if (!display) return 0;
  VolumeRenderer renderer;
  EXPECT_TRUE(renderer.init(&error)) << error;
  PaintSession session({kW, kH, kGrid}, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  RestingPen pen(strokeLeftDown());
  PaintLoopOptions options;
  options.max_seconds = seconds;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  PaintLoop loop(*display, renderer, session.volume(), Light{}, options);
  loop.attachPen(&pen, &session);
  PaintLoopSummary summary;
  EXPECT_TRUE(loop.run(nullptr, &summary, &error)) << error;
  std::filesystem::remove_all(dir);
  return session.strokesMapped();
}

TEST(PenRest, AStrokeEndsAfterTheRestTimeThoughThePenSendsNothing) {
  EXPECT_EQ(strokesAfterRest(0.8), 0u) << "0.8 s of rest: the stroke is still open";
  EXPECT_EQ(strokesAfterRest(3.0), 1u) << "3 s of rest (2 s needed): the stroke ended by itself";
}

}  // namespace
}  // namespace cb
