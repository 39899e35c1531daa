// Ink in the veil, with the product's defaults (grid 256, the default sky growing up to 8 boxes,
// config/brush.toml and config/mapping.toml) seen from a low view, 5° above the canvas, as the
// camera mode's drag leaves it: the upper part of the screen shows sky where the canvas does not
// reach, and the painter veils it (app/scene/drawable_region.h).
//   - exactly the footprint pixels outside the screen's veil edge are left out;
//   - a stroke wholly in the veil paints nothing, leaves the sky as it was (it used to grow the
//     sky to its widest and take about a second) and says how much ink it left out;
//   - a stroke across the veil's edge lands where the canvas reaches, the rest left out;
//   - the Session record says so, the journal replays to the same volume; a record without the
//     key (specification 1.8 and older) still places veiled ink on the fallback plane.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <unistd.h>

#include <gtest/gtest.h>

#include "app/core/config_paths.h"
#include "app/mapping/veil_ink.h"
#include "app/scene/drawable_region.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "tests/support/session_painter.h"

namespace cb {
namespace {

constexpr int kW = 1280, kH = 720;  // PaintSessionSettings' screen
constexpr int kGrid = 256;          // the painter's grid (cloudbrush paint --grid)

PaintSessionSettings productSettings() {
  PaintSessionSettings settings{kW, kH, kGrid};
  const BrushConfig brush = loadDefaultBrushConfig();
  settings.auto_end_still_ms = brush.stroke.auto_end_still_ms;
  settings.auto_end_light_ms = brush.stroke.auto_end_light_ms;
  return settings;
}

// The view the walk on X11 reached by dragging the default paint view down in camera mode (the
// painter logged it: 5° above the canvas, 62% of the screen paintable).
Camera lowView() {
  Camera c;
  c.eye = {0.0f, 0.159f, 2.159f};
  c.target = {0.0f, 0.0f, 0.368f};
  c.fov_y_deg = 35.0f;
  return c;
}

SyntheticStroke strokeAcross(glm::vec2 a, glm::vec2 b) {
  SyntheticStroke s;
  s.control_points = {a, glm::mix(a, b, 0.33f), glm::mix(a, b, 0.66f), b};
  return s;
}

double densitySum(const Volume& v) {
  double sum = 0.0;
  for (const glm::ivec3& brick : v.allocatedBrickList()) {
    const float* d = v.brick(brick);
    for (int i = 0; i < Volume::kBrickVoxels; ++i) sum += d[i];
  }
  return sum;
}

struct Painter : test::SessionPainter {
  explicit Painter(const PaintSessionSettings& settings)
      : SessionPainter(settings, loadDefaultBrushConfig(),
                       loadMappingConfig(configFile("mapping.toml"))) {
    apply(ui::SetCamera{lowView()});
  }
  // The stroke's samples fed one by one; the outcomes' veil pixels and mapping time summed.
  void paint(const SyntheticStroke& s) {
    for (const PenSample& sample : syntheticPenSamples(s, tablet, kW, kH, 200.0, t)) {
      const SampleOutcome out = session.feed(sample);
      veil_pixels += out.veil_pixels;
      if (out.stroke_mapped) mapping_ms += out.mapping.timings.total_ms;
      t = sample.t_ns;
    }
    t += 100'000'000;
  }
  long long veil_pixels = 0;
  double mapping_ms = 0.0;
};

// Where the low view's veil is (the sky above the horizon) and where the canvas is.
const glm::vec2 kVeilFrom(0.3f * kW, 0.15f * kH), kVeilTo(0.6f * kW, 0.2f * kH);

TEST(VeilInk, ExactlyThePixelsOutsideTheScreensVeilEdgeAreLeftOut) {
  const SkyExtent widest{kGrid, kMaxSkySpan};
  StrokeResult stroke;
  stroke.view.camera = lowView();
  stroke.footprint.width = kW;
  stroke.footprint.height = kH;
  stroke.footprint.values.assign(size_t(kW) * kH, 1.0f);
  const DrawableRegion region(stroke.view.camera, stroke.canvas, widest.worldMin(),
                              widest.worldMax(), kW, kH);
  const std::vector<uint8_t> mask = region.mask();
  long long veiled = 0;
  for (uint8_t m : mask) veiled += m == 0;
  ASSERT_GT(veiled, 0) << "the low view shows sky where the canvas does not reach";
  ASSERT_LT(veiled, (long long)(kW)*kH) << "and canvas below it";
  const long long cleared = leaveOutVeiledInk(&stroke, widest.worldMin(), widest.worldMax(), 0.05f);
  EXPECT_EQ(cleared, veiled);
  // The mask and the veil the screen draws (rowSpan runs) are the same pixels.
  long long differ = 0;
  for (size_t i = 0; i < mask.size(); ++i)
    differ += (stroke.footprint.values[i] > 0.0f) != (mask[i] != 0);
  EXPECT_EQ(differ, 0);
}

TEST(VeilInk, AStrokeWhollyInTheVeilPaintsNothingAndLeavesTheSkyAsItWas) {
  Painter p(productSettings());
  const SkyExtent before = p.session.sky();
  const auto t0 = std::chrono::steady_clock::now();
  p.paint(strokeAcross(kVeilFrom, kVeilTo));
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("a stroke wholly in the veil: mapping %.1f ms, stroke fed in %.0f ms, sky %d boxes\n",
              p.mapping_ms, ms, p.session.sky().span);
  EXPECT_EQ(p.session.strokesMapped(), 1u);
  EXPECT_GT(p.veil_pixels, 1000) << "the stroke's ink was in the veil and is counted as left out";
  EXPECT_EQ(densitySum(p.session.volume()), 0.0) << "nothing lands";
  EXPECT_EQ(p.session.sky().span, before.span) << "the sky does not grow for ink that cannot land";

  // The same stroke in a session recorded before (no veil_ink_left_out): the fallback plane, the
  // sky grown to its widest, as those journals replay.
  PaintSessionSettings old = productSettings();
  old.veil_ink_left_out = false;
  Painter q(old);
  q.paint(strokeAcross(kVeilFrom, kVeilTo));
  EXPECT_EQ(q.veil_pixels, 0);
  EXPECT_GT(densitySum(q.session.volume()), 0.0);
  EXPECT_EQ(q.session.sky().span, q.session.reachableSky().span);
}

TEST(VeilInk, AStrokeAcrossTheVeilsEdgeLandsWhereTheCanvasReachesAndReplays) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("cb_veil_ink_" + std::to_string(::getpid())))
          .string() +
      ".cbj";
  Painter p(productSettings());
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path));
  p.session.recordTo(&journal, p.t);
  // From the veil down onto the canvas (the horizon is at about 0.38 of the height).
  p.paint(strokeAcross({0.4f * kW, 0.2f * kH}, {0.45f * kW, 0.7f * kH}));
  EXPECT_EQ(p.session.strokesMapped(), 1u);
  EXPECT_GT(p.veil_pixels, 0) << "the part in the veil is left out";
  EXPECT_GT(densitySum(p.session.volume()), 0.0) << "the part over the canvas lands";
  journal.close();

  const JournalReadResult read = readJournal(path);
  bool said = false;
  for (const JournalRecord& r : read.records)
    said |= r.type == JournalRecordType::kSession &&
            std::string(r.text()).find("veil_ink_left_out = true") != std::string::npos;
  EXPECT_TRUE(said) << "the Session record says veiled ink is left out";
  const SessionReplay replay =
      replaySession(read, loadDefaultBrushConfig(), loadMappingConfig(configFile("mapping.toml")));
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete()) << (replay.problems.empty() ? "" : replay.problems[0]);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), volumeChecksum(p.session.volume()));
  std::filesystem::remove(path);
}

TEST(VeilInk, TheSessionRecordCarriesTheKeyAndOldRecordsLackIt) {
  PaintSessionSettings parsed;
  std::string error;
  ASSERT_TRUE(parseSessionSettings(formatSessionSettings(productSettings()), &parsed, &error))
      << error;
  EXPECT_TRUE(parsed.veil_ink_left_out);
  ASSERT_TRUE(parseSessionSettings("grid = 256\nsky_span = 4\nsky_max_span = 8\nformat = 2\n",
                                   &parsed, &error));
  EXPECT_FALSE(parsed.veil_ink_left_out) << "a record of specification 1.8 or older";
  EXPECT_FALSE(parseSessionSettings("grid = 256\nveil_ink_left_out = maybe\n", &parsed, &error));
  EXPECT_EQ(error, "session line 2: veil_ink_left_out: expected true or false, got 'maybe'");
}

}  // namespace
}  // namespace cb
