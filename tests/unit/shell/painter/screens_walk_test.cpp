// A first-time painter's walk at 1920×1080 with the product's defaults and the mouse as the pen
// (no tablet connected), through the real keymap, key routing (PaintScreen::onKey first, as
// FrameLoop does) and the painter's screen on EGL surfaceless (llvmpipe): what the screen says
// at each step. The start view is the framed paint view with a hint naming the mouse; the hint
// goes after the first stroke; a stroke held still 2 s ends with the button held; a save names
// a date-time file on screen; Delete says Ctrl+Z brings the cloud back; a mode key pressed in
// another mode says where it acts; q with unsaved work asks; the vacuum sphere sits under the
// pointer and two cuts leave a hole there; the light ball is on screen; the status line fits
// before the Menu button; the font holds every character of the labels and messages.
// CB_KEEP_FRAMES=DIR keeps each step's frame (PNG).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <regex>

#include "app/brush/brush_config.h"
#include "app/core/config_paths.h"
#include "app/mapping/mapping_config.h"
#include "app/render/image_io.h"
#include "app/scene/paint_camera.h"
#include "app/session/paint_session.h"
#include "app/shell/command_table.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/painter/painter_messages.h"
#include "app/shell/ui_overlay.h"
#include "drivers/core/clock.h"
#include "drivers/open_pen_source.h"

#include "tests/support/test_display.h"

namespace cb {
namespace {

constexpr int kW = 1920, kH = 1080;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

bool anyContains(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& l : lines)
    if (contains(l, part)) return true;
  return false;
}

// Summed over the allocated bricks (the sky is 1024×256×1024 voxels: never made dense here).
double density(const Volume& v) {
  double sum = 0;
  for (const glm::ivec3& b : v.allocatedBrickList()) {
    const float* voxels = v.brick(b);
    for (int i = 0; i < Volume::kBrickSize * Volume::kBrickSize * Volume::kBrickSize; ++i)
      sum += voxels[i];
  }
  return sum;
}

// Density summed over the voxels within `radius` of `centre` (world units).
double densityNear(const Volume& v, glm::vec3 centre, float radius) {
  const glm::vec3 lo = v.worldToVoxel(centre - glm::vec3(radius));
  const glm::vec3 hi = v.worldToVoxel(centre + glm::vec3(radius));
  double sum = 0;
  const glm::ivec3 dims = v.dims();
  for (int z = std::max(0, int(lo.z)); z <= std::min(dims.z - 1, int(hi.z)); ++z)
    for (int y = std::max(0, int(lo.y)); y <= std::min(dims.y - 1, int(hi.y)); ++y)
      for (int x = std::max(0, int(lo.x)); x <= std::min(dims.x - 1, int(hi.x)); ++x) {
        const glm::vec3 w = v.worldMin() + (glm::vec3(x, y, z) + 0.5f) * v.voxelSize();
        if (glm::length(w - centre) <= radius) sum += v.at(x, y, z);
      }
  return sum;
}

glm::vec2 project(const Camera& camera, glm::vec3 p) {
  const glm::vec4 clip =
      camera.projection(float(kW) / float(kH)) * camera.view() * glm::vec4(p, 1.0f);
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * float(kW), (0.5f - ndc.y * 0.5f) * float(kH)};
}

// Steps the screen as FrameLoop does, on a manual clock.
class Walk {
 public:
  Walk(Display& display, PaintScreen& screen, ManualClock& clock)
      : display_(display), screen_(screen), clock_(clock) {}
  // Keys as the loop routes them; returns the loop's quit reason ("" when it goes on).
  std::string keys(const char* list) {
    std::vector<DisplayEvent> events;
    std::string error;
    EXPECT_TRUE(parseKeyList(list, &events, &error)) << error;
    std::string quit;
    for (const DisplayEvent& e : events) {
      if (screen_.onKey(e, clock_.nowNs())) continue;
      const std::optional<Command> command = commandFor(e);
      if (!command) continue;
      if (*command == Command::kQuit && screen_.allowsQuit())
        quit = "quit";
      else
        screen_.onCommand(*command, clock_.nowNs());
    }
    if (quit.empty()) quit = frames(2);
    return quit;
  }
  void pointer(DisplayEvent::Kind kind, glm::vec2 at) {
    DisplayEvent e;
    e.kind = kind;
    e.button = 1;
    e.x = at.x;
    e.y = at.y;
    screen_.onPointer(e);
  }
  // A mouse stroke from a to b: press, moves, release; a frame every few moves.
  void mouseStroke(glm::vec2 a, glm::vec2 b, bool release = true) {
    pointer(DisplayEvent::Kind::PointerMove, a);
    pointer(DisplayEvent::Kind::PointerDown, a);
    for (int i = 1; i <= 24; ++i) {
      clock_.advance(8'000'000);
      pointer(DisplayEvent::Kind::PointerMove, glm::mix(a, b, float(i) / 24.0f));
      if (i % 8 == 0) frames(1);
    }
    if (release) {
      pointer(DisplayEvent::Kind::PointerUp, b);
      frames(3);  // the lit frame and its refinement
    }
  }
  std::string frames(int n) {
    std::string quit;
    for (int i = 0; i < n && quit.empty(); ++i) {
      FrameContext frame{display_, kW, kH, frame_, clock_.nowNs(), 1.0 / 60.0};
      clock_.advance(16'666'667);
      screen_.onPenSamples({});
      quit = screen_.update(frame);
      std::string error;
      EXPECT_TRUE(screen_.draw(frame, &error)) << error;
      EXPECT_TRUE(display_.present(&error)) << error;
      ++frame_;
    }
    return quit;
  }
  // Time passes with no frame drawn (the loop's update only).
  void idle(double seconds, int steps) {
    for (int i = 0; i < steps; ++i) {
      clock_.advance(int64_t(seconds / steps * 1e9));
      FrameContext frame{display_, kW, kH, frame_, clock_.nowNs(), seconds / steps};
      screen_.onPenSamples({});
      screen_.update(frame);
    }
  }
  void keep(const std::string& name) {
    const char* dir = std::getenv("CB_KEEP_FRAMES");
    if (!dir) return;
    writePng(std::string(dir) + "/" + name + ".png",
             readFramebufferRgba8(display_.framebuffer(), kW, kH));
  }

 private:
  Display& display_;
  PaintScreen& screen_;
  ManualClock& clock_;
  long frame_ = 0;
};

// The painter as `cloudbrush paint` starts it with no tablet (the mouse paints), and the steps
// of a first-time painter's walk, each a member below, in the order the test takes them.
class FirstTimePainter : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        (std::filesystem::temp_directory_path() / ("cb_screens_walk_" + std::to_string(::getpid())))
            .string();
    std::filesystem::create_directories(dir_ + "/state");
    std::string error;
    display_ = test::openTestDisplay(kW, kH, &error);
    ASSERT_TRUE(display_) << error;
    ASSERT_TRUE(renderer_.init(&error)) << error;
    // The product's defaults: the sky, brush and mapping `cloudbrush paint` starts with.
    PaintSessionSettings settings;
    settings.screen_width = kW;
    settings.screen_height = kH;
    settings.grid = 256;  // `cloudbrush paint`'s default (--grid)
    const BrushConfig brush = loadDefaultBrushConfig();
    settings.auto_end_still_ms = brush.stroke.auto_end_still_ms;
    settings.auto_end_light_ms = brush.stroke.auto_end_light_ms;
    ASSERT_GT(settings.auto_end_still_ms, 0) << "brush.toml ends a stroke held still";
    session_ = std::make_unique<PaintSession>(settings, brush,
                                              loadMappingConfig(configFile("mapping.toml")));
    session_->setQuietMapping(true);
    // No tablet: a pen source that finds none (the mouse paints).
    PenSourceOptions pen_options;
    pen_options.backend = "evdev";
    pen_options.device = "/nonexistent/cloudbrush-pen";
    pen_ = openPenSource(pen_options, &error);
    ASSERT_TRUE(pen_) << error;
    PaintLoopOptions options;  // the orbit at its default speed: the painter starts still anyway
    options.state_dir = dir_ + "/state";
    options.config_dir = dir_ + "/config";
    options.clock = &clock_;
    screen_ =
        std::make_unique<PaintScreen>(*display_, renderer_, session_->volume(), Light{}, options);
    screen_->attachPen(pen_.get(), session_.get());
    walk_ = std::make_unique<Walk>(*display_, *screen_, clock_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // The first screen: the framed paint view, still, the hint naming the mouse; a fresh frame.
  void firstScreen() {
    const auto t0 = std::chrono::steady_clock::now();
    walk_->frames(1);
    const double first_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("start view, first frame at %dx%d: %.0f ms (warm-up and UI set-up included)\n", kW,
                kH, first_ms);
    walk_->frames(2);
    walk_->keep("01_first_screen");
    EXPECT_EQ(screen_->shownCamera().eye, initialPaintCamera(session_->settings()).eye)
        << "the painter starts at the paint view, not orbiting";
    const std::vector<std::string> hint = screen_->hint();
    EXPECT_TRUE(anyContains(hint, msg::kHowToPaint.en));
    EXPECT_TRUE(anyContains(hint, msg::kHowToPaint.zh));
    EXPECT_TRUE(anyContains(hint, "mouse")) << "no tablet: the hint names the mouse";
    EXPECT_FALSE(contains(screen_->statusLine(), "plug one in"));
    EXPECT_TRUE(contains(screen_->statusLine(), "mouse"));
    ASSERT_TRUE(screen_->ui());
    EXPECT_TRUE(screen_->ui()->statusFits()) << screen_->statusLine();
  }

  // A mode key in another mode says where it acts, and does nothing.
  void modeKeysElsewhere() {
    EXPECT_EQ(session_->mode(), Mode::kPaint);
    const Camera before_r = session_->camera();
    walk_->keys("r");
    EXPECT_TRUE(contains(screen_->toast(), "R acts in Camera mode")) << screen_->toast();
    EXPECT_TRUE(contains(screen_->toast(), "相机")) << screen_->toast();
    EXPECT_EQ(session_->camera().eye, before_r.eye);
    walk_->keep("02_refused_key");
    const float altitude = session_->canvas().altitude;
    walk_->keys("pageup");
    EXPECT_TRUE(contains(screen_->toast(), "Canvas mode")) << screen_->toast();
    EXPECT_EQ(session_->canvas().altitude, altitude);
    walk_->keys("space");
    EXPECT_TRUE(contains(screen_->toast(), "Space acts in Camera mode")) << screen_->toast();
  }

  // The help overlay: H shows every mode's keys; Esc closes it and does not quit.
  void helpOverlay() {
    walk_->keys("h");
    EXPECT_TRUE(screen_->helpShown());
    walk_->keep("03_help");
    EXPECT_EQ(walk_->keys("esc"), "");
    EXPECT_FALSE(screen_->helpShown());
  }

  // A mouse stroke held still with the button down ends by itself after 2 s.
  void strokeHeldStill() {
    walk_->mouseStroke(a_, b_, /*release=*/false);
    EXPECT_TRUE(session_->engine().inStroke());
    EXPECT_TRUE(screen_->hint().empty()) << "the hint goes as the stroke begins";
    walk_->idle(2.5, 25);
    EXPECT_FALSE(session_->engine().inStroke()) << "resting still 2 s ends the stroke";
    EXPECT_EQ(session_->strokesMapped(), 1u);
    EXPECT_TRUE(contains(screen_->toast(), "Stroke ended")) << screen_->toast();
    walk_->pointer(DisplayEvent::Kind::PointerUp, b_);
    walk_->frames(3);
    walk_->keep("04_first_cloud");
    EXPECT_TRUE(screen_->hint().empty()) << "no hint after the first stroke";
    EXPECT_GT(density(session_->volume()), 0.0);
  }

  // Save: the screen names the file, a date and time.
  void save() {
    walk_->keys("ctrl+s");
    EXPECT_TRUE(contains(screen_->toast(), "Saved as cloud-")) << screen_->toast();
    EXPECT_TRUE(contains(screen_->toast(), "已保存")) << screen_->toast();
    // The painter's answer says where (a study's says which cloud, the folder only in the log).
    EXPECT_TRUE(contains(screen_->toast(), " in " + dir_ + "/state")) << screen_->toast();
    const std::string saved = std::filesystem::path(screen_->lastSaved()).filename().string();
    EXPECT_TRUE(std::regex_match(saved, std::regex(R"(cloud-\d{4}-\d\d-\d\d_\d\d-\d\d-\d\d\.vol)")))
        << saved;
    EXPECT_TRUE(std::filesystem::exists(screen_->lastSaved()));
    EXPECT_FALSE(screen_->unsavedWork());
    walk_->keep("05_saved");
  }

  // Delete: the screen says Ctrl+Z brings it back, and it does.
  void deleteAndUndo() {
    const double painted = density(session_->volume());
    walk_->keys("delete");
    EXPECT_EQ(density(session_->volume()), 0.0);
    EXPECT_TRUE(contains(screen_->toast(), "Ctrl+Z brings it back")) << screen_->toast();
    walk_->keep("06_cleared");
    walk_->keys("ctrl+z");
    EXPECT_DOUBLE_EQ(density(session_->volume()), painted);
  }

  // The vacuum under the pointer: two cuts at the cloud leave a hole there.
  void vacuumUnderPointer() {
    walk_->keys("4,v");
    ASSERT_EQ(session_->eraseTool(), EraseTool::kVacuum);
    const glm::vec2 target = 0.5f * (a_ + b_);
    walk_->pointer(DisplayEvent::Kind::PointerMove, target);
    walk_->frames(2);
    ASSERT_TRUE(screen_->vacuumCentre());
    const glm::vec2 shown = project(session_->camera(), *screen_->vacuumCentre());
    EXPECT_LT(glm::length(shown - target), 2.0f) << "the sphere sits under the pointer";
    const float radius = 0.5f * session_->eraseDiameter(EraseTool::kVacuum);
    const double before_cut = densityNear(session_->volume(), *screen_->vacuumCentre(), radius);
    EXPECT_GT(before_cut, 0.0) << "cloud under the pointer to cut";
    walk_->keep("07_vacuum");
    walk_->keys("space");
    walk_->keys("space");
    EXPECT_TRUE(contains(screen_->toast(), "Ctrl+Z brings it back")) << screen_->toast();
    // Inside the sphere's inner radius (volume_erase.h: the rim fades over the outer quarter),
    // less a voxel for the voxel centres' sampling.
    EXPECT_EQ(densityNear(session_->volume(), *screen_->vacuumCentre(),
                          0.75f * radius - session_->volume().voxelSize().x),
              0.0)
        << "a hole under the pointer";
    walk_->keep("08_vacuum_hole");
  }

  // Light mode: the ball is on screen.
  void lightBallOnScreen() {
    walk_->keys("5");
    const glm::vec2 ball = screen_->lightBallOnScreen();
    EXPECT_TRUE(ball.x > 0 && ball.x < kW && ball.y > 0 && ball.y < kH) << ball.x << "," << ball.y;
    walk_->keep("09_light");
  }

  // Ink in the veil: the front view (Camera mode's Down) shows sky above the horizon, where
  // the canvas does not reach; a stroke there is left out, said in both languages, and neither
  // grows the sky nor changes the cloud.
  void inkInTheVeil() {
    walk_->keys("1,down,3");
    const SkyExtent sky_before = session_->sky();
    const double cloud_before = density(session_->volume());
    const uint32_t strokes_before = session_->strokesMapped();
    walk_->mouseStroke({0.3f * kW, 0.12f * kH}, {0.6f * kW, 0.15f * kH}, /*release=*/false);
    walk_->keep("09b_veil_stroke");
    walk_->pointer(DisplayEvent::Kind::PointerUp, {0.6f * kW, 0.15f * kH});
    walk_->frames(3);
    walk_->keep("09c_veil_left_out");
    EXPECT_EQ(session_->strokesMapped(), strokes_before + 1);
    EXPECT_TRUE(contains(screen_->toast(), msg::kInkLeftOut.en)) << screen_->toast();
    EXPECT_TRUE(contains(screen_->toast(), msg::kInkLeftOut.zh)) << screen_->toast();
    EXPECT_EQ(session_->sky().span, sky_before.span)
        << "ink that cannot land does not grow the sky";
    EXPECT_EQ(density(session_->volume()), cloud_before);
    walk_->keys("1,r");
  }

  // The menu: every target labelled in both languages; the font draws every character.
  void menuLabels() {
    walk_->keys("m");
    walk_->frames(2);
    walk_->keep("10_menu");
    EXPECT_EQ(screen_->ui()->missingGlyphs(commandTableText() + painterMessagesText()), 0);
    for (int i = 0; i < int(Command::kCount); ++i) {
      float rect[4];
      if (!screen_->ui()->targetRect(Command(i), rect)) continue;
      const Bilingual label = commandLabelIn(Command(i), session_->mode());
      EXPECT_GT(std::string(label.en).size(), 0u) << commandName(Command(i));
      EXPECT_GT(std::string(label.zh).size(), 0u) << commandName(Command(i));
    }
    walk_->keys("esc");
    EXPECT_FALSE(screen_->menuOpen()) << "Esc closes the menu first";
  }

  // q with unsaved work asks; a second q (or Y) quits. Saved: q quits at once.
  void quitAsks() {
    walk_->keys("3");
    walk_->mouseStroke({0.3f * kW, 0.4f * kH}, {0.45f * kW, 0.42f * kH});
    ASSERT_TRUE(screen_->unsavedWork());
    EXPECT_EQ(walk_->keys("q"), "") << "q alone does not end a session with unsaved work";
    EXPECT_TRUE(contains(screen_->toast(), "press Esc again or Y")) << screen_->toast();
    walk_->keep("11_quit_asks");
    EXPECT_EQ(walk_->keys("y"), "q (confirmed)");
  }

  std::string dir_;
  std::unique_ptr<Display> display_;
  VolumeRenderer renderer_;
  std::unique_ptr<PaintSession> session_;
  std::unique_ptr<PenSource> pen_;
  ManualClock clock_{1'000'000'000};
  std::unique_ptr<PaintScreen> screen_;
  std::unique_ptr<Walk> walk_;
  // The first stroke's ends (the vacuum cuts between them).
  glm::vec2 a_{0.38f * kW, 0.5f * kH}, b_{0.62f * kW, 0.52f * kH};
};

TEST_F(FirstTimePainter, IsToldWhatToDoAndLosesNothing) {
  firstScreen();
  if (HasFatalFailure()) return;
  modeKeysElsewhere();
  if (HasFatalFailure()) return;
  helpOverlay();
  if (HasFatalFailure()) return;
  strokeHeldStill();
  if (HasFatalFailure()) return;
  save();
  if (HasFatalFailure()) return;
  deleteAndUndo();
  if (HasFatalFailure()) return;
  vacuumUnderPointer();
  if (HasFatalFailure()) return;
  lightBallOnScreen();
  if (HasFatalFailure()) return;
  inkInTheVeil();
  if (HasFatalFailure()) return;
  menuLabels();
  if (HasFatalFailure()) return;
  quitAsks();
  if (HasFatalFailure()) return;
}

// Every command has a label in both languages, and the mode keys act only in their modes.
TEST(ScreensWalk, EveryCommandIsLabelledInBothLanguages) {
  for (int i = 0; i < int(Command::kCount); ++i) {
    const Bilingual label = commandLabel(Command(i));
    EXPECT_GT(std::string(label.en).size(), 0u) << commandName(Command(i));
    bool chinese = false;
    for (const char* p = label.zh; *p; ++p) chinese |= (static_cast<unsigned char>(*p) & 0x80) != 0;
    EXPECT_TRUE(chinese) << commandName(Command(i)) << ": no Chinese label";
  }
  EXPECT_TRUE(commandActsIn(Command::kResetCamera, Mode::kCamera));
  EXPECT_FALSE(commandActsIn(Command::kResetCamera, Mode::kPaint));
  EXPECT_FALSE(commandActsIn(Command::kRaise, Mode::kPaint));
  EXPECT_FALSE(commandActsIn(Command::kNextEraseTool, Mode::kPaint));
  EXPECT_FALSE(commandActsIn(Command::kSpace, Mode::kPaint));
  EXPECT_TRUE(commandActsIn(Command::kSpace, Mode::kErase));
  EXPECT_TRUE(commandActsIn(Command::kNextStyle, Mode::kPaint)) << "T is global";
  // The help lists each mode's own keys under that mode.
  bool r_in_camera = false;
  for (const HelpSection& s : helpSections(false))
    for (const std::string& line : s.lines)
      r_in_camera |= std::string(s.title.en) == "Camera" && line.rfind("R\t", 0) == 0;
  EXPECT_TRUE(r_in_camera);
}

}  // namespace
}  // namespace cb
