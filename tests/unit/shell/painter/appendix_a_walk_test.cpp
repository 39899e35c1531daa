// The thesis's guided tutorial (Appendix A, 26 steps) walked through the real keymap, pen events
// and the painter's screen on EGL surfaceless (llvmpipe), with the product's defaults (256³ sky,
// default brush and mapping configs, the default paint view) at 640×360 (CB_WALK_SIZE: another
// size, see walkSize). The state is checked
// after each step; each mode is shot with the pen menu open and compared with a golden
// (CB_UPDATE_GOLDENS=1 rewrites them; look at them); the walk's journal replays to the same
// volume.
//
// The walk drives the screen the way FrameLoop does (keys → commandFor → onCommand; pen samples
// → onPenSamples; update; draw; present) so keys can be interleaved with strokes.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "app/brush/synthetic_strokes.h"
#include "app/core/config_paths.h"
#include "app/render/image_io.h"
#include "app/scene/paint_camera.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/synthetic_session.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/ui_overlay.h"
#include "drivers/core/clock.h"
#include "drivers/replay/replay_pen_source.h"

#include "tests/support/recorded_painter.h"
#include "tests/support/test_display.h"

namespace cb {
namespace {

// The walk's size: 640×360, the size of its goldens; or CB_WALK_SIZE=WxH to walk it as a
// participant sees it (1920x1080) with CB_KEEP_FRAMES=DIR: every state check runs, and the mode
// shots are kept for a person to look at but not compared (there are no goldens at that size;
// the test prints so).
struct WalkSize {
  int w = 640, h = 360;
  bool goldens = true;
};
WalkSize walkSize() {
  WalkSize size;
  if (const char* env = std::getenv("CB_WALK_SIZE")) {
    int w = 0, h = 0;
    if (std::sscanf(env, "%dx%d", &w, &h) == 2 && w >= 320 && h >= 180 && w <= 7680 && h <= 4320 &&
        !(w == size.w && h == size.h)) {
      size = {w, h, false};
    } else if (!(w == size.w && h == size.h)) {
      std::fprintf(stderr, "CB_WALK_SIZE=%s: expected WxH within 320x180..7680x4320\n", env);
      std::exit(2);
    }
  }
  return size;
}
const WalkSize kSize = walkSize();
const int kW = kSize.w, kH = kSize.h;

std::string goldenPath(const std::string& name) {
  return std::string(CB_SOURCE_DIR) + "/tests/unit/shell/painter/golden/" + name + ".png";
}

void expectMatchesGolden(const std::string& name, const ImageRgba8& image) {
  if (const char* keep = std::getenv("CB_KEEP_FRAMES"))
    writePng(std::string(keep) + "/" + name + ".png", image);
  if (!kSize.goldens) {
    std::printf("%s: not compared: the goldens are 640x360, this walk is %dx%d (CB_WALK_SIZE)\n",
                name.c_str(), kW, kH);
    return;
  }
  if (std::getenv("CB_UPDATE_GOLDENS")) {
    writePng(goldenPath(name), image);
    return;
  }
  ASSERT_TRUE(std::filesystem::exists(goldenPath(name)))
      << "no golden " << goldenPath(name) << " (CB_UPDATE_GOLDENS=1 creates it)";
  const ImageRgba8 golden = readPng(goldenPath(name));
  ASSERT_EQ(golden.pixels.size(), image.pixels.size());
  size_t off = 0;
  double sum = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const int e = std::abs(int(image.pixels[i]) - int(golden.pixels[i]));
    sum += e;
    off += e > 8;
  }
  const double mean = sum / double(image.pixels.size());
  if (mean > 0.5 || off > image.pixels.size() / 200) writePng(name + ".actual.png", image);
  EXPECT_LE(mean, 0.5) << name << ": mean channel error (see " << name << ".actual.png)";
  EXPECT_LE(off, image.pixels.size() / 200) << name << ": channels off by more than 8";
}

double density(const Volume& v) {
  double sum = 0;
  for (float d : v.toDense()) sum += d;
  return sum;
}

// Steps the screen as the frame loop does.
class Walk {
 public:
  Walk(Display& display, PaintScreen& screen, PenSource& pen, ManualClock& clock)
      : display_(display), screen_(screen), pen_(pen), clock_(clock) {
    clock_.set(now_);
  }
  void keys(const char* list) {
    std::vector<DisplayEvent> events;
    std::string error;
    ASSERT_TRUE(parseKeyList(list, &events, &error)) << error;
    for (const DisplayEvent& e : events) {
      const std::optional<Command> command = commandFor(e);
      ASSERT_TRUE(command) << list;
      screen_.onCommand(*command, now_);
    }
    frames(2);
  }
  // Plays `samples` pen samples from the replay pen, a few per frame.
  void pen(size_t samples) {
    std::vector<PenSample> batch;
    while (samples > 0) {
      batch.clear();
      for (int i = 0; i < 3 && samples > 0; ++i, --samples) pen_.poll(0, batch);
      screen_.onPenSamples(batch);
      frames(1);
    }
    frames(3);  // the lit frame and its refinement
  }
  void frames(int n) {
    for (int i = 0; i < n; ++i) {
      FrameContext frame{display_, kW, kH, frame_, now_, 1.0 / 60.0};
      now_ += 16'666'667;
      clock_.set(now_);  // messages time out on the walk's time line, not the machine's speed
      screen_.onPenSamples({});
      screen_.update(frame);
      std::string error;
      ASSERT_TRUE(screen_.draw(frame, &error)) << error;
      last_ = readFramebufferRgba8(display_.framebuffer(), kW, kH);
      ASSERT_TRUE(display_.present(&error)) << error;
      ++frame_;
    }
  }
  const ImageRgba8& lastFrame() const { return last_; }
  // CB_KEEP_FRAMES=DIR keeps the step's last frame as DIR/step_NN_<what>.png (to look at).
  void keep(const char* what) {
    if (const char* dir = std::getenv("CB_KEEP_FRAMES")) {
      char name[96];
      std::snprintf(name, sizeof name, "/step_%02d_%s.png", ++kept_, what);
      writePng(std::string(dir) + name, last_);
    }
  }

 private:
  Display& display_;
  PaintScreen& screen_;
  PenSource& pen_;
  ManualClock& clock_;
  int64_t now_ = 1'000'000'000;
  long frame_ = 0;
  int kept_ = 0;
  ImageRgba8 last_;
};

SyntheticStroke strokeAcross(glm::vec2 a, glm::vec2 b) {
  SyntheticStroke s;
  s.control_points = {a, glm::mix(a, b, 0.33f) + glm::vec2(0, -12),
                      glm::mix(a, b, 0.66f) + glm::vec2(0, 12), b};
  return s;
}

// The pen's part of the walk, written as a journal for the replay backend: strokes left and right
// (steps 9, 12), a rub-out over the left one (15), calligraphy (24: three strokes of 永).
// Returns each stroke's sample count.
std::vector<size_t> writeTutorialPen(const std::string& pen_path,
                                     const PaintSessionSettings& settings, const BrushConfig& brush,
                                     const MappingConfig& mapping) {
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  const std::vector<SyntheticStroke> pen_strokes = {
      strokeAcross({0.25f * kW, 0.45f * kH}, {0.42f * kW, 0.55f * kH}),  // left
      strokeAcross({0.58f * kW, 0.45f * kH}, {0.75f * kW, 0.55f * kH}),  // right
      strokeAcross({0.25f * kW, 0.45f * kH}, {0.42f * kW, 0.55f * kH}),  // rub the left out
      strokeAcross({0.35f * kW, 0.35f * kH}, {0.65f * kW, 0.36f * kH}),  // 永: horizontal
      strokeAcross({0.5f * kW, 0.3f * kH}, {0.51f * kW, 0.7f * kH}),     // vertical
      strokeAcross({0.48f * kW, 0.5f * kH}, {0.3f * kW, 0.68f * kH})};   // sweep left
  std::vector<size_t> counts;
  {
    JournalWriter journal;
    EXPECT_TRUE(journal.open(pen_path)) << pen_path;
    PaintSession recorder(settings, brush, mapping);
    recorder.recordTo(&journal, 0);
    recorder.setDevice(tablet, 0);
    int64_t t = 1'000'000'000;
    for (const SyntheticStroke& s : pen_strokes) {
      const std::vector<PenSample> samples = syntheticPenSamples(s, tablet, kW, kH, 200.0, t);
      for (const PenSample& sample : samples) journal.appendPenSample(sample);
      counts.push_back(samples.size());
      t = samples.back().t_ns + 200'000'000;
    }
  }
  return counts;
}

bool holdsASavedCloud(const std::string& folder) {
  bool saved = false;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    saved |= entry.path().extension() == ".vol";
  return saved;
}

// The walk's journal replays whole, to the volume the walk painted.
void expectReplaysTo(const std::string& journal, const BrushConfig& brush,
                     const MappingConfig& mapping, const Volume& painted) {
  const SessionReplay replay = replaySession(readJournal(journal), brush, mapping);
  ASSERT_TRUE(replay.session);
  EXPECT_TRUE(replay.complete()) << replay.journal_error
                                 << (replay.problems.empty() ? "" : replay.problems[0]);
  EXPECT_EQ(volumeChecksum(replay.session->volume()), volumeChecksum(painted));
}

TEST(AppendixA, TheGuidedTutorialWalksThroughTheRealScreens) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_appendix_a_" + std::to_string(::getpid())))
          .string();
  std::filesystem::create_directories(dir + "/state");
  MappingConfig mapping = loadMappingConfig(configFile("mapping.toml"));
  const BrushConfig brush = loadDefaultBrushConfig();
  const PaintSessionSettings settings{kW, kH, 256};

  const std::string pen_path = dir + "/pen.cbj";
  const std::vector<size_t> counts = writeTutorialPen(pen_path, settings, brush, mapping);
  ASSERT_EQ(counts.size(), 6u);

  std::string error;
  test::RecordedPainter painter;
  ASSERT_TRUE(painter.open(settings, brush, mapping, dir + "/walk.cbj", 0, &error)) << error;
  Display& display = *painter.display;
  PaintSession& session = *painter.session;
  ReplayOptions replay_options;
  replay_options.realtime = false;
  replay_options.batch = 1;
  ReplayPenSource pen(pen_path, replay_options);
  PaintLoopOptions options;
  options.orbit_degrees_per_second = 0.0f;
  ManualClock clock;
  options.clock = &clock;
  options.state_dir = dir + "/state";
  options.config_dir = dir + "/config";
  PaintScreen screen(display, painter.renderer, session.volume(), Light{}, options);
  screen.attachPen(&pen, &session);
  Walk walk(display, screen, pen, clock);
  walk.frames(2);  // the pen connects; its calibration is chosen
  const auto shoot = [&](const char* name) {
    walk.keys("m");  // the menu open over the mode
    walk.frames(2);  // ImGui shows a new window on its second frame
    expectMatchesGolden(name, walk.lastFrame());
    walk.keys("m");
  };
  const float voxel = session.volume().voxelSize().y;

  walk.keys("delete");  // 1
  walk.keep("delete_all");
  EXPECT_EQ(density(session.volume()), 0.0);
  walk.keys("1,r");  // 2
  EXPECT_EQ(session.mode(), Mode::kCamera);
  EXPECT_EQ(session.camera().eye, initialPaintCamera(settings).eye);
  shoot("mode_camera");
  walk.keys("2");  // 3
  EXPECT_EQ(session.mode(), Mode::kCanvas);
  shoot("mode_canvas");
  // 4: altitude 96 of 256 voxels: 32 steps down from the middle.
  for (int i = 0; i < 32; ++i) walk.keys("pagedown");
  EXPECT_NEAR(session.canvas().altitude, -1.0f + 96.0f * voxel, 1e-5f);
  walk.keep("canvas_altitude_96");
  walk.keys("1");   // 5
  walk.keys("up");  // 6: top-down
  EXPECT_GT(viewElevationDeg(session.camera()), 80.0f);
  walk.keep("top_view");
  walk.keys("3");  // 7
  EXPECT_EQ(session.mode(), Mode::kPaint);
  shoot("mode_paint");
  const BrushKind before = session.selectedBrush();
  walk.keys("b");  // 8
  EXPECT_NE(session.selectedBrush(), before);
  walk.pen(counts[0]);  // 9
  walk.keep("stroke_left");
  EXPECT_EQ(session.strokesMapped(), 1u);
  const std::vector<float> after_left = session.volume().toDense();
  EXPECT_GT(density(session.volume()), 0.0);
  walk.keys("c");       // 10
  walk.keys("c");       // 11
  walk.pen(counts[1]);  // 12
  walk.keep("stroke_right");
  EXPECT_EQ(session.strokesMapped(), 2u);
  walk.keys("ctrl+z");  // 13
  walk.keep("undo");
  EXPECT_TRUE(after_left == session.volume().toDense()) << "undo removed exactly the right stroke";
  walk.keys("4");  // 14
  EXPECT_EQ(session.mode(), Mode::kErase);
  shoot("mode_erase");
  const double left = density(session.volume());
  walk.keys("plus,plus,plus,plus");
  walk.pen(counts[2]);  // 15: rub the left stroke out
  walk.keep("rub_out");
  EXPECT_LT(density(session.volume()), 0.3 * left);
  walk.keys("1,r");  // 16, 17
  EXPECT_EQ(session.camera().eye, initialPaintCamera(settings).eye);
  walk.keys("2");                                      // 18
  for (int i = 0; i < 32; ++i) walk.keys("pagedown");  // 19: altitude 64
  EXPECT_NEAR(session.canvas().altitude, -1.0f + 64.0f * voxel, 1e-5f);
  walk.keys("1,up,3");                                      // 20–22
  walk.keys("b");                                           // 23
  for (int i = 3; i < 6; ++i) walk.pen(counts[size_t(i)]);  // 24: calligraphy
  walk.keep("calligraphy");
  EXPECT_EQ(session.strokesMapped(), 5u);
  walk.keys("5");
  shoot("mode_light");
  walk.keys("1");  // 25
  // 26: the menu, and "save" chosen on it.
  walk.keys("m");
  walk.frames(2);
  float rect[4];
  ASSERT_TRUE(screen.ui() && screen.ui()->targetRect(Command::kSave, rect));
  walk.keys("ctrl+s");  // the same command the Save target gives (the tap is tested elsewhere)
  walk.keep("saved");
  EXPECT_TRUE(holdsASavedCloud(dir + "/state"));
  painter.journal.close();
  expectReplaysTo(painter.recorded, brush, mapping, session.volume());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
