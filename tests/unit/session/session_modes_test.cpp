// Modes and erase through the session model, and a journal with modes, erase, undo and redo
// replaying to the same volume.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/core/parallel_for.h"
#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/tools/procedural_mesh.h"
#include "tests/support/session_painter.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 180, kGrid = 64;

double total(const Volume& v) {
  double sum = 0;
  for (float d : v.toDense()) sum += d;
  return sum;
}

struct Painter : test::SessionPainter {
  Painter() : SessionPainter({kW, kH, kGrid}, BrushConfig{}, MappingConfig{}) {}
};

TEST(SessionModes, OnlyPaintModePaintsAndRubOutCutsAlongTheView) {
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kW, kH);
  Painter p;
  p.apply(ui::SetMode{Mode::kCamera});
  p.stroke(strokes[0]);
  EXPECT_EQ(p.session.strokesMapped(), 0u) << "a drag in camera mode paints nothing";
  EXPECT_EQ(total(p.session.volume()), 0.0);
  p.apply(ui::SetMode{Mode::kPaint});
  p.stroke(strokes[0]);
  ASSERT_EQ(p.session.strokesMapped(), 1u);
  const double painted = total(p.session.volume());
  ASSERT_GT(painted, 0.0);
  // Rub-out along the same path removes most of the cloud inside the canvas range.
  p.apply(ui::SetMode{Mode::kErase});
  p.apply(ui::SetEraseTool{EraseTool::kRubOut});
  p.apply(ui::SetEraseDiameter{EraseTool::kRubOut, 0.4f});
  const size_t steps = p.session.history().undoable();
  p.stroke(strokes[0]);
  const double rubbed = total(p.session.volume());
  EXPECT_LT(rubbed, 0.5 * painted) << painted << " -> " << rubbed;
  EXPECT_EQ(p.session.history().undoable(), steps + 1) << "one rub is one history step";
  p.apply(ui::Undo{});
  EXPECT_EQ(total(p.session.volume()), painted);
}

TEST(SessionModes, VacuumCutsASoftSphereAndNothingOutsideIt) {
  Painter p;
  Volume& v = p.session.volume();
  v.fill(0.5f);
  p.apply(ui::DeleteAll{});  // a step, then refill as the base of the vacuum test
  v.fill(0.5f);
  const glm::vec3 centre(0.1f, 0.2f, -0.1f);
  p.apply(ui::VacuumCut{centre, 0.4f});
  const auto at = [&](glm::vec3 w) {
    const glm::ivec3 i = glm::ivec3(v.worldToVoxel(w));
    return v.at(i.x, i.y, i.z);
  };
  EXPECT_EQ(at(centre), 0.0f) << "the sphere's core is empty";
  EXPECT_EQ(at(centre + glm::vec3(0.5f, 0, 0)), 0.5f) << "outside the sphere nothing changes";
  const float rim = at(centre + glm::vec3(0.37f, 0, 0));
  EXPECT_GT(rim, 0.0f);
  EXPECT_LT(rim, 0.5f) << "the boundary is smooth (§3.5.1)";
  // The vacuum centre follows the pen: x/z on the canvas plane, the height from pressure.
  MappedSample pen;
  pen.x_px = kW / 2.0;
  pen.y_px = kH / 2.0;
  pen.pressure = 1.0f;
  glm::vec3 high, low;
  ASSERT_TRUE(p.session.vacuumCentre(pen, &high));
  pen.pressure = 0.0f;
  ASSERT_TRUE(p.session.vacuumCentre(pen, &low));
  EXPECT_FLOAT_EQ(high.y, v.worldMax().y);
  EXPECT_FLOAT_EQ(low.y, v.worldMin().y);
  EXPECT_FLOAT_EQ(high.x, low.x);
}

TEST(SessionModes, AJournalWithModesEraseUndoAndRedoReplaysExactly) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("cb_session_modes_" + std::to_string(::getpid()) + ".cbj"))
                               .string();
  const std::vector<SyntheticStroke> strokes = referencePaintStrokes(kW, kH);
  uint64_t sum = 0;
  {
    Painter p;
    JournalWriter journal;
    ASSERT_TRUE(journal.open(path)) << journal.error();
    p.session.recordTo(&journal, 0);
    p.stroke(strokes[0]);
    p.apply(ui::SetCamera{Camera::reference().orbited(30.0f)});
    p.apply(ui::SetCanvas{0.2f, 0.5f});
    p.apply(ui::SetBrush{BrushKind::k2D});
    p.stroke(strokes[1]);
    p.apply(ui::Undo{});
    p.apply(ui::Redo{});
    p.apply(ui::SetMode{Mode::kErase});
    p.apply(ui::VacuumCut{glm::vec3(0.0f, 0.0f, 0.0f), 0.3f});
    p.stroke(strokes[0]);  // rub-out
    p.apply(ui::Undo{});
    p.apply(ui::SetMode{Mode::kPaint});
    p.apply(ui::SetLight{glm::vec3(-1, 2, 0), glm::vec3(1, 0.9f, 0.8f)});
    p.stroke(strokes[1]);
    journal.close();
    sum = volumeChecksum(p.session.volume());
  }
  const SessionReplay replay = replaySession(readJournal(path), BrushConfig{}, MappingConfig{});
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete()) << replay.journal_error
                                 << (replay.problems.empty() ? "" : replay.problems[0]);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), sum);
  EXPECT_EQ(replay.session->mode(), Mode::kPaint);
  EXPECT_EQ(replay.session->canvas().altitude, 0.2f);
  std::filesystem::remove(path);
}

// §7.7.5 problem 3: a pen resting on the tablet ends its stroke by itself, and the next stroke
// needs a lift first; from the samples' own times, so a replay ends the same stroke.
TEST(SessionModes, AStrokeHeldStillEndsByItself) {
  Painter p;
  const SyntheticStroke stroke = referencePaintStrokes(kW, kH)[0];
  std::vector<PenSample> samples = syntheticPenSamples(stroke, p.tablet, kW, kH, 200.0, p.t);
  // Insert a 2.5 s rest (tip down, not moving) in the middle of the stroke.
  size_t middle = 0;
  for (size_t i = 0; i < samples.size(); ++i)
    if (samples[i].tipDown()) middle = i;
  middle = middle / 2 + 10;
  std::vector<PenSample> rest;
  for (int k = 1; k <= 500; ++k) {
    PenSample s = samples[middle];
    s.t_ns += int64_t(k) * 5'000'000;
    rest.push_back(s);
  }
  for (size_t i = middle + 1; i < samples.size(); ++i) samples[i].t_ns += 2'500'000'000;
  samples.insert(samples.begin() + long(middle) + 1, rest.begin(), rest.end());
  size_t ended_at = 0;
  for (size_t i = 0; i < samples.size(); ++i)
    if (p.session.feed(samples[i]).auto_ended) ended_at = i;
  EXPECT_EQ(p.session.strokesMapped(), 1u) << "one stroke, ended by the rest; no second one";
  ASSERT_GT(ended_at, middle);
  const double ms = double(samples[ended_at].t_ns - samples[middle].t_ns) / 1e6;
  EXPECT_GE(ms, 2000.0);
  EXPECT_LE(ms, 2100.0) << "the 1€ filter settles within a few samples";
  // After a lift, strokes work again.
  p.t = samples.back().t_ns + 100'000'000;
  p.stroke(stroke);
  EXPECT_EQ(p.session.strokesMapped(), 2u);
  // Off (0), the rest does not end the stroke.
  PaintSessionSettings off{kW, kH, kGrid};
  off.auto_end_still_ms = off.auto_end_light_ms = 0;
  PaintSession session(off, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  session.setDevice(p.tablet, 0);
  bool ended = false;
  for (const PenSample& s : samples) ended |= session.feed(s).auto_ended;
  EXPECT_FALSE(ended);
  EXPECT_EQ(session.strokesMapped(), 1u);
}

// A pen moving on while resting lightly (held down only by the calibration's contact hysteresis,
// MappedSample::light_contact) ends its stroke after auto_end_light_ms; pressing at the down
// threshold and above does not. Contact and lightness come from the one contact decision.
TEST(SessionModes, AStrokeTouchedOnlyLightlyEndsByItself) {
  for (const float share : {0.03f, 0.08f}) {  // of the pressure range: under / over contact_down
    Painter p;
    const SyntheticStroke stroke = referencePaintStrokes(kW, kH)[0];
    std::vector<PenSample> samples = syntheticPenSamples(stroke, p.tablet, kW, kH, 200.0, p.t);
    size_t first = samples.size(), last = 0;
    for (size_t i = 0; i < samples.size(); ++i)
      if (samples[i].tipDown()) first = std::min(first, i), last = i;
    ASSERT_LT(first + 40, last);
    const size_t from = first + 4;  // light from here on: 20 ms after tip-down
    for (size_t i = from; i <= last; ++i)
      samples[i].pressure = share,
      samples[i].pressure_raw = int32_t(share * float(p.tablet.pressure_max));
    size_t ended_at = 0;
    bool ended = false;
    for (size_t i = 0; i < samples.size(); ++i)
      if (p.session.feed(samples[i]).auto_ended) ended_at = i, ended = true;
    const double light_ms = double(samples[last].t_ns - samples[from].t_ns) / 1e6;
    ASSERT_GT(light_ms, 860.0) << "the stroke must stay light longer than auto_end_light_ms";
    if (share < 0.05f) {
      ASSERT_TRUE(ended) << "a light touch for " << light_ms << " ms did not end the stroke";
      const double ms = double(samples[ended_at].t_ns - samples[from].t_ns) / 1e6;
      EXPECT_GE(ms, 800.0);
      EXPECT_LE(ms, 850.0);
    } else {
      EXPECT_FALSE(ended) << "pressing at " << share << " of the range is not a light touch";
    }
    EXPECT_EQ(p.session.strokesMapped(), 1u);
  }
}

// A picture placed as a cloud is an edit like a stroke: painted from the current view, undone,
// journalled, replayed; a bad file is refused by name and leaves the cloud as it was.
TEST(SessionModes, APlacedPictureIsAnEditLikeAStroke) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_place_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir);
  ImageRgba8 disc;
  disc.width = disc.height = 64;
  disc.pixels.assign(64 * 64 * 4, 255);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool inside = (x - 32) * (x - 32) + (y - 32) * (y - 32) < 24 * 24;
      disc.pixels[size_t(y * 64 + x) * 4 + 3] = inside ? 255 : 0;
    }
  writePng(dir + "/disc.png", disc);
  const std::string journal_path = dir + "/placed.cbj";
  uint64_t sum = 0;
  {
    Painter p;
    JournalWriter journal;
    ASSERT_TRUE(journal.open(journal_path));
    p.session.recordTo(&journal, 0);
    std::string error;
    EXPECT_FALSE(p.session.apply(ui::PlaceShape{false, dir + "/missing.png"}, 0, &error));
    EXPECT_NE(error.find("missing.png"), std::string::npos) << error;
    EXPECT_EQ(total(p.session.volume()), 0.0);
    p.apply(ui::PlaceShape{false, dir + "/disc.png"});
    const double placed = total(p.session.volume());
    EXPECT_GT(placed, 0.0);
    p.apply(ui::Undo{});
    EXPECT_EQ(total(p.session.volume()), 0.0);
    p.apply(ui::Redo{});
    EXPECT_EQ(total(p.session.volume()), placed);
    // A model too, and a bad one refused by name with the cloud untouched.
    writeObj(dir + "/torus.obj", makeDisplacedTorus(0.5f, 0.2f, 0.1f, 32, 24));
    TriangleMesh open = makeDisplacedTorus(0.5f, 0.2f, 0.0f, 16, 12);
    open.triangles.pop_back();
    writeObj(dir + "/open.obj", open);
    const Volume before_bad = p.session.volume();
    EXPECT_FALSE(p.session.apply(ui::PlaceShape{true, dir + "/open.obj"}, 0, &error));
    EXPECT_NE(error.find("open.obj"), std::string::npos) << error;
    EXPECT_EQ(volumeChecksum(p.session.volume()), volumeChecksum(before_bad));
    p.apply(ui::PlaceShape{true, dir + "/torus.obj"});
    EXPECT_GT(total(p.session.volume()), placed);
    journal.close();
    sum = volumeChecksum(p.session.volume());
  }
  for (int threads : {1, 8}) {
    setWorkerThreads(threads);
    const SessionReplay replay =
        replaySession(readJournal(journal_path), BrushConfig{}, MappingConfig{});
    ASSERT_TRUE(replay.session);
    EXPECT_TRUE(replay.complete()) << (replay.problems.empty() ? "" : replay.problems[0]);
    EXPECT_EQ(volumeChecksum(replay.session->volume()), sum) << threads << " threads";
  }
  setWorkerThreads(0);
  std::filesystem::remove_all(dir);
}

TEST(SessionModes, FormatOneSessionsKeepTheReferenceView) {
  PaintSessionSettings old;
  std::string error;
  ASSERT_TRUE(
      parseSessionSettings("screen_width = 320\nscreen_height = 180\ngrid = 64\n", &old, &error))
      << error;
  EXPECT_EQ(old.format, 1);
  EXPECT_EQ(initialPaintCamera(old).eye, Camera::reference().eye);
  PaintSessionSettings now{kW, kH, kGrid};
  EXPECT_NE(initialPaintCamera(now).eye, Camera::reference().eye);
}

}  // namespace
}  // namespace cb
