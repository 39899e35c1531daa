// PaintScreen's commands (paint_screen.h): keys, pen-menu taps and side buttons, each acting in
// the modes command_table.h gives it and answering on screen (PaintScreen::tell); the quit
// confirmation and the save. Kept out of paint_screen.cpp, which draws.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include <fcntl.h>
#include <unistd.h>

#include <xkbcommon/xkbcommon-keysyms.h>

#include "app/brush/brush_config.h"
#include "app/scene/paint_camera.h"
#include "app/shell/command_table.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/mouse_pen.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/painter/painter_messages.h"
#include "app/volume/volume_file.h"

namespace cb {
namespace {

// How long a first Esc or q waits for the second (or Y) before it is forgotten: time to read
// the question in two languages; the question shows as long.
constexpr int64_t kQuitConfirmNs = 10'000'000'000;

// "cloud-2026-11-29_14-05-09.vol" in `dir` (local time: what the person's clock says), with
// "-2", "-3" … when a save in the same second exists.
std::filesystem::path readableSavePath(const std::string& dir) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[40];
  std::strftime(stamp, sizeof stamp, "cloud-%Y-%m-%d_%H-%M-%S", &local);
  std::filesystem::path path = std::filesystem::path(dir) / (std::string(stamp) + ".vol");
  for (int n = 2; std::filesystem::exists(path); ++n)
    path = std::filesystem::path(dir) / (std::string(stamp) + "-" + std::to_string(n) + ".vol");
  return path;
}

// saveVolume to a temporary name, fsync, rename, fsync the folder: a crash leaves the old
// files and never half a cloud under the final name.
void saveVolumeAtomically(const Volume& volume, const std::filesystem::path& path) {
  const std::filesystem::path temp = path.string() + ".part";
  saveVolume(volume, temp.string());
  if (const int fd = ::open(temp.c_str(), O_RDONLY); fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  std::filesystem::rename(temp, path);
  if (const int dir = ::open(path.parent_path().c_str(), O_RDONLY | O_DIRECTORY); dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

}  // namespace

Camera PaintScreen::presetView(Command command) const {
  const Camera base = session_ ? session_->camera() : Camera::reference();
  const float distance = glm::length(base.eye - base.target);
  Camera c = base;
  switch (command) {
    case Command::kViewTop:  // straight down, the screen's top towards -z
      c.eye = c.target + distance * glm::normalize(glm::vec3(0.0f, 1.0f, 0.02f));
      break;
    case Command::kViewFront:
      c.eye = c.target + distance * glm::normalize(glm::vec3(0.0f, 0.15f, 1.0f));
      break;
    case Command::kViewLeft:
      c.eye = c.target + distance * glm::normalize(glm::vec3(-1.0f, 0.15f, 0.0f));
      break;
    default:  // perspective, reset
      c = session_ ? initialPaintCamera(session_->settings()) : Camera::reference();
      break;
  }
  return c;
}

bool PaintScreen::visitorAllows(Command command) const {
  // Visitor mode: painting, erasing, camera, undo and start again; no operator
  // commands (files, statistics, canvas and light set-up, style, quit).
  switch (command) {
    case Command::kQuit:
    case Command::kModeCanvas:
    case Command::kModeLight:
    case Command::kSave:
    case Command::kOpen:
    case Command::kToggleStats:
    case Command::kNextStyle:
    case Command::kRaise:
    case Command::kLower:
      return false;
    default:
      return true;
  }
}

void PaintScreen::tell(const std::string& text, int64_t for_ns) {
  // A kiosk visitor is told in the kiosk's words, or not at all (the log has it).
  toast_ = visitorWords() ? visitorAnswer(text, visitor_text_) : text;
  toast_until_ns_ = clockNs() + (for_ns > 0 ? for_ns : kToastNs);
  say(text);
}

const std::string& PaintScreen::toast() const {
  static const std::string none;
  return clockNs() < toast_until_ns_ ? toast_ : none;
}

bool PaintScreen::unsavedWork() const {
  if (!hasPaint()) return false;
  const Volume& v = session_->volume();
  return !(v.instanceId() == saved_volume_ && v.generation() == saved_generation_) ||
         session_->engine().inStroke();
}

bool PaintScreen::onKey(const DisplayEvent& event, int64_t t_ns) {
  if (replay_view_ || event.kind != DisplayEvent::Kind::KeyDown) return false;
  const bool plain = (event.modifiers & (DisplayEvent::kCtrl | DisplayEvent::kAlt)) == 0;
  const bool armed = quit_armed_until_ns_ > clockNs();
  if (armed && plain && (event.keysym == 'y' || event.keysym == 'Y')) {
    quit_confirmed_ = true;  // update() ends the loop
    return true;
  }
  const std::optional<Command> command = commandForKey(event.keysym, event.modifiers);
  if (command != Command::kQuit) {
    quit_armed_until_ns_ = 0;  // any other key: the quit is off
    return false;
  }
  // Esc closes what is open over the painting first (help, menu), then asks.
  if (event.keysym == XKB_KEY_Escape && (help_open_ || menu_open_)) {
    help_open_ = false;
    setMenu(false, t_ns);
    return true;
  }
  if (!allowsQuit() || !unsavedWork() || armed) return false;  // the loop quits (or refuses)
  quit_armed_until_ns_ = clockNs() + kQuitConfirmNs;
  tell(msg::kQuitAsk.oneLine(), kQuitConfirmNs);
  return true;
}

void PaintScreen::onCommand(Command command, int64_t t_ns) {
  if (options_.visitor_mode && !visitorAllows(command))
    return tell(msg::kForOperator.oneLine() + " (" + keyLabel(command) + ")");
  // Mode keys act only in their mode (command_table.h); elsewhere the person is told where.
  if (session_ && !commandActsIn(command, session_->mode()))
    return tell(refusalText(command, session_->mode()));
  switch (command) {
    case Command::kModeCamera:
    case Command::kModeCanvas:
    case Command::kModePaint:
    case Command::kModeErase:
    case Command::kModeLight:
      apply(ui::SetMode{Mode(int(command) - int(Command::kModeCamera))}, t_ns);
      vacuum_centre_.reset();
      return;
    case Command::kMenu:
      return setMenu(!menu_open_, t_ns);
    case Command::kHelp:
      help_open_ = !help_open_;
      return;
    case Command::kNextBrush:
    case Command::kNextMapping:
    case Command::kNextStyle:
    case Command::kNextEraseTool:
      return onChoiceCommand(command, t_ns);
    case Command::kResetCamera:
    case Command::kViewTop:
    case Command::kViewFront:
    case Command::kViewLeft:
    case Command::kViewPerspective:
    case Command::kPanDrag:
    case Command::kPanLeft:
    case Command::kPanRight:
    case Command::kPanUp:
    case Command::kPanDown:
    case Command::kGoodView:
      return onViewCommand(command, t_ns);
    case Command::kSpace:
      return onSpace(t_ns);
    case Command::kSmaller:
    case Command::kLarger:
    case Command::kRaise:
    case Command::kLower:
      return onSizeCommand(command, t_ns);
    case Command::kBrushSmaller:
    case Command::kBrushLarger:
      return stepBrushSize(command == Command::kBrushLarger ? 1 : -1, t_ns);
    case Command::kToggleCircles:
      show_circles_ = !show_circles_;
      refined_ = false;
      return;
    case Command::kToggleStats:
      show_stats_ = !show_stats_;
      refined_ = false;
      return;
    case Command::kDeleteAll:
    case Command::kUndo:
    case Command::kRedo:
    case Command::kOpen:
    case Command::kSave:
      return onCloudCommand(command, t_ns);
    case Command::kMorph:
    case Command::kWind:
    case Command::kWindDirection:
    case Command::kApplyAnimation:
    case Command::kLeaveAnimation:
      return onAnimationCommand(command, t_ns);
    case Command::kQuit:           // the frame loop's (onKey asks first)
    case Command::kOperatorPause:  // the study runner's (study_run_screen.h)
    case Command::kOperatorSkip:
    case Command::kOperatorAbort:
    case Command::kCount:
      return;
  }
}

void PaintScreen::stepBrushSize(int steps, int64_t t_ns) {
  if (!session_) return say("no pen session: the brush size is not used");
  const float size = steppedBrushSize(session_->brushSize(), steps);
  if (size == session_->brushSize())
    return tell(steps > 0 ? "Brush size: already the largest / 笔刷已最大"
                          : "Brush size: already the smallest / 笔刷已最小");
  std::string error;
  if (!session_->apply(ui::SetBrushSize{size}, t_ns, &error)) return say(error);
  char text[160];
  std::snprintf(text, sizeof text,
                "Brush size %.2f from the next stroke ([ ] or the mouse wheel) / 笔刷大小 %.2f",
                double(size), double(size));
  tell(text);
}

void PaintScreen::onChoiceCommand(Command command, int64_t t_ns) {
  if (!session_) return say(std::string(commandName(command)) + ": no pen session");
  if (command == Command::kNextBrush) {
    const BrushKind order[3] = {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton};
    int next = 0;
    for (int i = 0; i < 3; ++i)
      if (order[i] == session_->selectedBrush()) next = (i + 1) % 3;
    apply(ui::SetBrush{order[next]}, t_ns);
  } else if (command == Command::kNextMapping) {
    // hybrid -> ray-marching -> sheet (a wide, thin, flat layer for stratus) -> hybrid
    const MappingMethod m = session_->mappingMethod();
    apply(ui::SetMapping{m == MappingMethod::kHybrid        ? MappingMethod::kRayMarching
                         : m == MappingMethod::kRayMarching ? MappingMethod::kSheet
                                                            : MappingMethod::kHybrid},
          t_ns);
  } else if (command == Command::kNextStyle) {
    const RenderStyle now = currentStyle();
    size_t next = 0;
    for (size_t i = 0; i < kAllRenderStyles.size(); ++i)
      if (kAllRenderStyles[i] == now) next = (i + 1) % kAllRenderStyles.size();
    apply(ui::SetStyle{renderStyleName(kAllRenderStyles[next])}, t_ns);
  } else {
    apply(ui::SetEraseTool{session_->eraseTool() == EraseTool::kVacuum ? EraseTool::kRubOut
                                                                       : EraseTool::kVacuum},
          t_ns);
    vacuum_centre_.reset();
  }
}

void PaintScreen::onViewCommand(Command command, int64_t t_ns) {
  if (!session_) return say("no pen session: the view is the bundled cloud's");
  switch (command) {
    case Command::kPanDrag:
      pan_drag_ = !pan_drag_;
      return say(pan_drag_ ? "camera mode: a pen drag pans the view (P orbits again)"
                           : "camera mode: a pen drag orbits (P pans)");
    case Command::kPanLeft:
    case Command::kPanRight:
    case Command::kPanUp:
    case Command::kPanDown: {
      // A twentieth of the screen height per press, in the arrow's direction (the view moves,
      // so the scene moves the other way).
      const Camera c = session_->camera();
      const float step =
          0.05f * float(display_.height()) * c.worldPerPixelAtTarget(display_.height());
      const float right = command == Command::kPanRight  ? step
                          : command == Command::kPanLeft ? -step
                                                         : 0.0f;
      const float up = command == Command::kPanUp     ? step
                       : command == Command::kPanDown ? -step
                                                      : 0.0f;
      return apply(ui::SetCamera{c.panned(right, up), CameraMove::kPan}, t_ns);
    }
    case Command::kGoodView: {
      const SkyExtent reach = session_->reachableSky();
      return apply(ui::SetCamera{nearestGoodPaintView(session_->camera(), session_->canvas(),
                                                      reach.worldMin(), reach.worldMax(),
                                                      display_.width(), display_.height())},
                   t_ns);
    }
    default:  // reset and the preset views
      orbit_degrees_ = 0.0f;
      return apply(ui::SetCamera{presetView(command), CameraMove::kView}, t_ns);
  }
}

void PaintScreen::onSpace(int64_t t_ns) {
  if (session_ && session_->mode() == Mode::kErase) {
    if (session_->eraseTool() != EraseTool::kVacuum)
      return tell("Space cuts with the vacuum: press V for it / 空格用于吸除：按 V 切换");
    if (!vacuum_centre_) return tell(msg::kVacuumPlace.oneLine());
    apply(ui::VacuumCut{*vacuum_centre_, 0.5f * session_->eraseDiameter(EraseTool::kVacuum)}, t_ns);
    return tell(msg::kVacuumCut.oneLine());
  }
  orbiting_ = !orbiting_;
  refined_ = false;
  if (!orbiting_ && orbit_degrees_ != 0.0f && session_) {
    const Camera here = shownCamera();
    orbit_degrees_ = 0.0f;
    apply(ui::SetCamera{here}, t_ns);
  }
  tell(orbiting_ ? msg::kRotating.oneLine() : msg::kRotationStopped.oneLine());
}

void PaintScreen::onSizeCommand(Command command, int64_t t_ns) {
  if (!session_) return;
  const Mode mode = session_->mode();
  if (command == Command::kRaise || command == Command::kLower) {
    const Canvas c = session_->canvas();
    const Volume& v = session_->volume();
    const float step = v.voxelSize().y * (command == Command::kRaise ? 1.0f : -1.0f);
    return apply(
        ui::SetCanvas{std::clamp(c.altitude + step, v.worldMin().y, v.worldMax().y), c.thickness},
        t_ns);
  }
  const bool larger = command == Command::kLarger;
  const float factor = larger ? 1.25f : 0.8f;
  if (mode == Mode::kErase) {
    const EraseTool tool = session_->eraseTool();
    apply(
        ui::SetEraseDiameter{tool, std::clamp(session_->eraseDiameter(tool) * factor, 0.02f, 2.0f)},
        t_ns);
  } else if (mode == Mode::kCamera) {
    // Zoom for pens without side buttons: + closer, − further.
    apply(ui::SetCamera{session_->camera().zoomed(larger ? 0.8f : 1.25f), CameraMove::kZoom}, t_ns);
  } else if (mode == Mode::kCanvas) {
    const Canvas c = session_->canvas();
    apply(ui::SetCanvas{c.altitude, std::clamp(c.thickness * factor, 0.02f, 2.0f)}, t_ns);
  } else if (mode == Mode::kPaint && mouse_) {
    mouse_->setPressure(mouse_->pressure() + (larger ? 0.1f : -0.1f));
    tell("mouse pressure " + std::to_string(mouse_->pressure()).substr(0, 4));
  } else if (mode == Mode::kPaint && tipOnlyPen()) {
    tip_only_pressure_ = std::clamp(tip_only_pressure_ + (larger ? 0.1f : -0.1f), 0.05f, 1.0f);
    tell("pen without pressure: strokes at " + std::to_string(tip_only_pressure_).substr(0, 4));
  } else if (mode == Mode::kLight) {
    // Warmer (−) or cooler (+): towards an evening orange or a noon white-blue.
    const Light l = session_->light();
    const glm::vec3 towards =
        larger ? glm::vec3(0.92f, 0.96f, 1.0f) : glm::vec3(1.0f, 0.72f, 0.48f);
    apply(ui::SetLight{l.direction, glm::mix(l.colour, towards, 0.25f)}, t_ns);
  }
}

void PaintScreen::onCloudCommand(Command command, int64_t t_ns) {
  if (!session_) return say(std::string(commandName(command)) + ": no pen session");
  switch (command) {
    case Command::kDeleteAll:
      if (options_.visitor_mode && options_.before_start_again && hasPaint())
        options_.before_start_again();  // the kiosk keeps the finished cloud first
      apply(ui::DeleteAll{}, t_ns);
      return tell(msg::kCleared.oneLine());
    case Command::kUndo:
      if (!session_->history().canUndo()) return tell(msg::kNothingToUndo.oneLine());
      return apply(ui::Undo{}, t_ns);
    case Command::kRedo:
      if (!session_->history().canRedo()) return tell(msg::kNothingToRedo.oneLine());
      return apply(ui::Redo{}, t_ns);
    case Command::kOpen:
      return openLastSaved(t_ns);
    default:
      return saveCloud();
  }
}

void PaintScreen::openLastSaved(int64_t t_ns) {
  // The most recently saved cloud of the save folder (--open FILE opens any file).
  std::filesystem::path newest;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(saveDir(), ec))
    if (entry.path().extension() == ".vol" &&
        (newest.empty() || entry.last_write_time() > std::filesystem::last_write_time(newest, ec)))
      newest = entry.path();
  if (newest.empty()) return tell("No saved cloud yet in " + saveDir());
  try {
    std::string error;
    if (session_->replaceVolume(loadVolume(newest.string()), t_ns, newest.string(), &error))
      tell("Opened " + newest.filename().string() + " / 已打开");
    else
      tell(error);
  } catch (const std::exception& e) {
    tell(std::string("Open failed, the cloud is unchanged: ") + e.what());
  }
}

const std::string& PaintScreen::saveDir() const {
  return options_.save_dir.empty() ? options_.state_dir : options_.save_dir;
}

void PaintScreen::saveCloud() {
  try {
    std::filesystem::create_directories(saveDir());
    const std::filesystem::path path = readableSavePath(saveDir());
    saveVolumeAtomically(session_->volume(), path);
    saved_volume_ = session_->volume().instanceId();
    saved_generation_ = session_->volume().generation();
    last_saved_ = path.string();
    // The painter says the file's name and its folder; a caller's words (the study runner's:
    // which task's cloud) replace them, and the log has the whole path.
    say("saved " + path.string());
    const std::string name = path.filename().string();
    tell(save_words_ ? save_words_(path.string())
                     : std::string(msg::kSavedAs.en) + " " + name + " in " +
                           path.parent_path().string() + " / " + msg::kSavedAs.zh + " " + name);
  } catch (const std::exception& e) {
    tell(std::string(msg::kSaveFailed.en) + ": " + e.what() + " / " + msg::kSaveFailed.zh);
  }
}

}  // namespace cb
