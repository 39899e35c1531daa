#include "app/shell/painter/paint_screen.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "app/scene/drawable_region.h"
#include "app/scene/paint_camera.h"
#include "app/shell/keymap.h"
#include "app/shell/painter/animation_preview.h"
#include "app/shell/painter/hud_items.h"
#include "app/shell/painter/mouse_pen.h"
#include "app/shell/painter/painter_messages.h"
#include "app/shell/ui_overlay.h"
#include "app/volume/volume_file.h"
#include "calibration/profile_store.h"
#include "drivers/core/clock.h"
#include "drivers/core/pen_source.h"
#include "drivers/core/tip_only_pressure.h"

namespace cb {
namespace {

int64_t monotonicNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// Milliseconds since the pen sample stamped `t_ns`, when the pen's clock is the monotonic one
// (a kernel timestamp, a replayed pen restamped on its real time line: a lift at most 10 s
// ago); 0 for a replay fed as fast as polled, which carries its recorded times.
double msSinceSample(int64_t t_ns) {
  const int64_t since = MonotonicClock().nowNs() - t_ns;
  return t_ns > 0 && since >= 0 && since < 10'000'000'000 ? double(since) / 1e6 : 0.0;
}

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
  return values[values.size() / 2];
}

bool sameCamera(const Camera& a, const Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fov_y_deg == b.fov_y_deg;
}

// The camera turned about its target: `yaw` about the world up axis, `pitch` towards the pole,
// kept between 2° and 89.5° above or below the horizon so the view never flips.
Camera orbitCamera(const Camera& base, float yaw_deg, float pitch_deg) {
  Camera c = base.orbited(yaw_deg);
  glm::vec3 offset = c.eye - c.target;
  const float distance = glm::length(offset);
  const float elevation = std::asin(std::clamp(offset.y / distance, -1.0f, 1.0f));
  const float next =
      std::clamp(elevation + glm::radians(pitch_deg), glm::radians(-89.5f), glm::radians(89.5f));
  const glm::vec2 horizontal = glm::normalize(glm::vec2(offset.x, offset.z) + glm::vec2(1e-6f));
  offset = distance *
           glm::vec3(std::cos(next) * horizontal.x, std::sin(next), std::cos(next) * horizontal.y);
  c.eye = c.target + offset;
  return c;
}

// The light ball's sphere about the scene origin: radius 1.5 (the home box's corners), or less
// so the whole sphere is on screen from this camera (a ball off screen cannot be dragged).
float lightBallRadius(const Camera& camera) {
  const float distance = glm::length(camera.eye);
  return std::min(1.5f, 0.75f * distance * std::tan(glm::radians(0.5f * camera.fov_y_deg)));
}

// The light ball: where the pen's ray meets the light ball's sphere about the scene origin (the
// nearest point of the ray when it misses); its direction from the origin is the sun's.
glm::vec3 lightDirectionAt(const Camera& camera, float x, float y, int w, int h) {
  glm::vec3 origin, dir;
  camera.pixelRay(x, y, w, h, &origin, &dir);
  const float radius = lightBallRadius(camera);
  const float b = glm::dot(origin, dir);
  const float c = glm::dot(origin, origin) - radius * radius;
  const float disc = b * b - c;
  glm::vec3 p = disc >= 0.0f ? origin + (-b - std::sqrt(disc)) * dir : origin - b * dir;
  if (glm::length(p) < 1e-4f) p = glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(p);
}

glm::vec2 project(const Camera& camera, glm::vec3 p, int w, int h) {
  const glm::vec4 clip = camera.projection(float(w) / float(h)) * camera.view() * glm::vec4(p, 1);
  if (clip.w <= 1e-6f) return glm::vec2(-1e6f);
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return {(ndc.x * 0.5f + 0.5f) * float(w), (0.5f - ndc.y * 0.5f) * float(h)};
}

}  // namespace

bool PaintScreen::SceneKey::operator==(const SceneKey& o) const {
  return volume == o.volume && generation == o.generation && sameCamera(camera, o.camera) &&
         light.direction == o.light.direction && light.colour == o.light.colour &&
         light.extinction == o.light.extinction && stats == o.stats && style == o.style;
}

PaintScreen::PaintScreen(Display& display, VolumeRenderer& renderer, const Volume& volume,
                         const Light& light, const PaintLoopOptions& options)
    : display_(display),
      renderer_(renderer),
      volume_(volume),
      light_(light),
      options_(options),
      orbiting_(options.orbit_degrees_per_second != 0.0f),
      moving_path_{{options.moving_frames, options.target_frame_ms},
                   {options.moving_frames, options.target_frame_ms}},
      moving_scale_(std::clamp(options.moving_scale, options.min_moving_scale, 1.0f)),
      show_stats_(options.show_stats_overlay),
      show_circles_(options.show_circles_overlay) {
  light_drag_scale_ = std::clamp(options.moving_scale, options.min_light_drag_scale, 1.0f);
  options_.render.cast_at_volume_detail = options.cast_at_volume_detail;
}

PaintScreen::~PaintScreen() = default;

void PaintScreen::attachPen(PenSource* pen, PaintSession* session) {
  pen_ = pen;
  // A new session (the kiosk's next visitor) gets the device and calibration again.
  if (session_ && session != session_) {
    last_connection_ = -1;
    menu_open_ = false;
    drag_camera_.reset();
    drag_canvas_.reset();
    drag_light_.reset();
    refined_ = false;
    if (mouse_ && session) {
      session->setDevice(mouse_->device(), clockNs());
      session->setCalibration(CalibrationProfile{}, clockNs());
    }
  }
  session_ = session;
  // A resumed session opens with the menu as it was.
  if (session_) menu_open_ = session_->menuOpen();
  // The painter starts at the session's paint view, still, ready for the first stroke.
  if (showsSession()) {
    orbiting_ = false;
    orbit_degrees_ = 0.0f;
    refined_ = false;
  }
}

bool PaintScreen::showsSession() const {
  return session_ && (pen_connected_once_ || replay_view_ || !options_.visitor_mode);
}

bool PaintScreen::showReplay(PaintSession* session, std::string* error) {
  session_ = session;
  replay_view_ = true;
  pen_connected_once_ = true;  // the session's cloud is shown from the first frame
  orbiting_ = false;
  orbit_degrees_ = 0.0f;
  menu_open_ = session_->menuOpen();
  return paintingSetUp(error);
}

void PaintScreen::replayedSample(const SampleOutcome& outcome) {
  ++pen_samples_;
  afterSample(outcome, std::chrono::steady_clock::now());
}

void PaintScreen::setMenu(bool open, int64_t t_ns) {
  if (open == menu_open_) return;
  menu_open_ = open;
  say(open ? "menu open" : "menu closed");
  std::string error;
  if (session_ && !session_->apply(ui::ShowMenu{open}, t_ns, &error)) say(error);
}

const Volume& PaintScreen::shownVolume() const {
  if (animation_ && animation_->active()) return animation_->shown();
  return showsSession() ? session_->volume() : volume_;
}

SyncStats PaintScreen::syncShown() {
  // The light's coarse preview (reduced_light_sweep.h): while the light ball is dragged and the
  // first frame at its release, and while an animation plays (each frame's volume lit coarse).
  const bool playing = animationPlaying();
  const int divisor = playing                                 ? options_.animation_light_divisor
                      : drag_light_ || light_release_pending_ ? options_.light_drag_divisor
                                                              : 1;
  renderer_.setLightPreviewDivisor(divisor, playing ? VolumeRenderer::LightPreviewOf::kEveryChange
                                                    : VolumeRenderer::LightPreviewOf::kLightMoves);
  return renderer_.sync(shownVolume(), shownLight(),
                        playing ? ChangeDetail::kSlots : ChangeDetail::kTexels);
}

Light PaintScreen::shownLight() const {
  if (drag_light_) return *drag_light_;
  return showsSession() ? session_->light() : light_;
}

Camera PaintScreen::shownCamera() const {
  if (drag_camera_) return *drag_camera_;
  const Camera base = session_ ? session_->camera() : Camera::reference();
  return orbit_degrees_ != 0.0f ? base.orbited(orbit_degrees_) : base;
}

PaintScreen::SceneKey PaintScreen::currentKey() const {
  const Volume& v = shownVolume();
  return SceneKey{v.instanceId(), v.generation(), shownCamera(),
                  shownLight(),   show_stats_,    currentStyle()};
}

RenderStyle PaintScreen::currentStyle() const {
  if (!session_) return options_.render.style;
  return parseRenderStyle(session_->styleName()).value_or(RenderStyle::kThesis);
}

void PaintScreen::say(const std::string& message) {
  if (message == last_message_) return;
  last_message_ = message;
  std::fprintf(stderr, "cloudbrush: %s\n", message.c_str());
}

void PaintScreen::apply(const UiChange& change, int64_t t_ns) {
  if (!session_) {
    say("no pen session: " + formatUiChange(change).text + " has nothing to change");
    return;
  }
  std::string error;
  if (!session_->apply(change, t_ns, &error)) return say(error);
  say(formatUiChange(change).text);
  warnIfEdgeOn();
}

void PaintScreen::warnIfEdgeOn() {
  // §7.7.5 problem 2: from a near edge-on view little of the canvas can be painted; say so and
  // offer the nearest good view (G takes it).
  // Judged over where a stroke can land: the sky as wide as it may grow.
  const SkyExtent reach = session_->reachableSky();
  const PaintViewAssessment view =
      assessPaintView(session_->camera(), session_->canvas(), reach.worldMin(), reach.worldMax(),
                      display_.width(), display_.height());
  edge_on_ = session_->mode() == Mode::kPaint && !view.good;
  if (!edge_on_) notice_.clear();
  if (edge_on_) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "this view is nearly edge-on to the canvas (%.0f° above it, %.0f%% of the "
                  "screen can be painted): press G for the nearest good view",
                  double(view.elevation_deg), 100.0 * view.fill_fraction);
    say(text);
    notice_ = text;
  }
}

int64_t PaintScreen::clockNs() const {
  // The frame loop's clock (a study replay runs on the recording's time line), else monotonic.
  return options_.clock ? options_.clock->nowNs() : monotonicNowNs();
}

void PaintScreen::selectCalibration(uint64_t tool_serial) {
  const PenDeviceInfo& device = pen_->deviceInfo();
  session_->setDevice(device, clockNs());
  ProfileSelection selection =
      selectProfile(device, tool_serial, options_.config_dir, options_.state_dir);
  for (const std::string& message : selection.messages)
    std::fprintf(stderr, "cloudbrush: calibration: %s\n", message.c_str());
  std::fprintf(stderr, "cloudbrush: calibration from %s\n", selection.source.c_str());
  session_->setCalibration(selection.profile, clockNs());
}

bool PaintScreen::reselectCalibration() {
  if (!pen_ || !session_ || pen_->connection() != PenConnection::kConnected) return false;
  selectCalibration(tool_serial_);
  return true;
}

void PaintScreen::onPenSamples(const std::vector<PenSample>& samples) {
  if (!pen_ || !session_) return;
  const int connection = int(pen_->connection());
  if (connection != last_connection_) {
    last_connection_ = connection;
    const std::string status = pen_->statusMessage();
    std::fprintf(stderr, "cloudbrush: pen %s (%s)%s%s\n", penConnectionName(pen_->connection()),
                 pen_->backendName(), status.empty() ? "" : ": ", status.c_str());
    if (pen_->connection() == PenConnection::kConnected) {
      if (!pen_connected_once_) {
        pen_connected_once_ = true;  // from now on the session's volume is shown and painted
        refined_ = false;
        if (options_.on_first_connection) options_.on_first_connection();
      }
      selectCalibration(tool_serial_);
    }
  }
  for (PenSample sample : samples) {  // a pen without pressure paints at the chosen level
    applyTipOnlyPressure(sample, pen_->deviceInfo(), tip_only_pressure_);
    feedSample(sample);
    last_pen_sample_ = sample;
  }
}

// A pen resting still on the tablet sends nothing (evdev reports changes only, and many
// tablets stop reporting), so the session could not time the rest after which an open stroke
// ends by itself (thesis §7.7.5, problem 3; PaintSession auto_end_still_ms). While the tip is
// down and no sample came for 50 ms, the last one is fed again with the time now, as the mouse
// held still is. A recording has its own samples; a sample whose time is not within a minute
// before now is on another time line than the loop's clock, and is not repeated.
void PaintScreen::repeatRestingPen() {
  if (!pen_ || !session_ || !session_->engine().inStroke()) return;
  if (pen_->connection() != PenConnection::kConnected || !last_pen_sample_.in_proximity ||
      !(last_pen_sample_.buttons & kPenTip) || std::strcmp(pen_->backendName(), "replay") == 0)
    return;
  const int64_t now = clockNs();
  if (now - last_pen_sample_.t_ns < 50'000'000 || now - last_pen_sample_.t_ns > 60'000'000'000)
    return;
  last_pen_sample_.t_ns = now;
  feedSample(last_pen_sample_);
}

bool PaintScreen::tipOnlyPen() const {
  return pen_ && pen_->connection() == PenConnection::kConnected &&
         !penHasPressure(pen_->deviceInfo());
}

void PaintScreen::feedSample(const PenSample& sample) {
  if (sample.tool_serial != 0 && sample.tool_serial != tool_serial_) {
    tool_serial_ = sample.tool_serial;  // a profile may be for one tool: select again
    selectCalibration(tool_serial_);
  }
  if (sample.in_proximity && orbiting_) {
    // Painting needs a still camera (§3.3): the auto-rotation stops where it is, and that
    // view becomes the session's camera.
    orbiting_ = false;
    refined_ = false;
    if (orbit_degrees_ != 0.0f) {
      const Camera here = shownCamera();
      orbit_degrees_ = 0.0f;
      apply(ui::SetCamera{here}, sample.t_ns);
    }
  }
  // The on-screen UI holds the pen while the menu is open or when the pen comes down on a UI
  // target; the change is made only while the pen is up, so no stroke is cut short.
  const bool capture = menu_open_ || pointer_over_ui_;
  if (capture != session_->penCaptured() && !pen_events_.down() && !session_->engine().inStroke())
    apply(ui::PenCapture{capture}, sample.t_ns);
  const auto received = std::chrono::steady_clock::now();  // pen-up -> lit counts the mapping
  const SampleOutcome outcome = session_->feed(sample);
  ++pen_samples_;
  if (outcome.stroke_mapped) lift_sample_ns_ = sample.t_ns;
  afterSample(outcome, received);
  events_.clear();
  pen_events_.derive(outcome.mapped, &events_);
  pen_x_ = float(outcome.mapped.x_px);
  pen_y_ = float(outcome.mapped.y_px);
  pen_in_proximity_ = outcome.mapped.in_proximity;
  if (ui_ && outcome.mapped.in_proximity)
    ui_->pointer(float(outcome.mapped.x_px), float(outcome.mapped.y_px), outcome.mapped.contact);
  for (const PenEvent& event : events_) {
    // Side buttons always reach the screen; the rest only when the UI does not hold the pen.
    const bool button =
        event.kind == PenEvent::Kind::kButtonDown || event.kind == PenEvent::Kind::kButtonUp;
    if (button || !session_->penCaptured()) handleEvent(event, outcome.mapped);
  }
}

void PaintScreen::afterSample(const SampleOutcome& outcome,
                              std::chrono::steady_clock::time_point received) {
  if (outcome.stroke_began)
    overlay_.beginFootprint(session_->footprintWidth(), session_->footprintHeight());
  if (!outcome.changed.empty())
    texels_this_frame_ += overlay_.upload(session_->engine().footprint(), outcome.changed);
  if (outcome.auto_ended && !replay_view_) tell(msg::kStrokeEnded.oneLine());
  if (outcome.stroke_mapped) {
    // Ink in the veil (where the canvas is out of reach) is left out (app/mapping/veil_ink.h);
    // a session recorded before that places it on the mapping's fallback plane. Said so, once
    // per stroke.
    long off_canvas = 0;
    for (const MappedSphere& sphere : outcome.mapping.spheres) off_canvas += !sphere.on_canvas;
    if (outcome.veil_pixels > 0 && !replay_view_)
      tell(msg::kInkLeftOut.oneLine());
    else if (off_canvas > 0 && !replay_view_)
      tell(msg::kInkOnFallback.oneLine());
    ++strokes_seen_;
    lift_time_ = received;
    lift_mapping_ms_ = outcome.mapping.timings.total_ms;
    lit_pending_ = true;
    // The cloud replaces the ink: the footprint is cleared as the lit scene is drawn.
    overlay_.beginFootprint(session_->footprintWidth(), session_->footprintHeight());
  }
  cursor_.screen_px =
      glm::vec2(float(outcome.mapped.preview_x_px), float(outcome.mapped.preview_y_px));
  cursor_.visible = outcome.mapped.in_proximity;
}

void PaintScreen::onPointer(const DisplayEvent& event) {
  // A mouse (X11) drives the on-screen UI, and paints when no tablet is connected.
  if (event.kind == DisplayEvent::Kind::PointerDown && (event.button == 4 || event.button == 5)) {
    // The wheel: the mouse's stand-in for pressure is the brush size (away: larger).
    if (session_ && session_->mode() == Mode::kPaint)
      stepBrushSize(event.button == 4 ? 1 : -1, clockNs());
    return;
  }
  if (event.kind == DisplayEvent::Kind::PointerDown && event.button == 1) mouse_down_ = true;
  if (event.kind == DisplayEvent::Kind::PointerUp && event.button == 1) mouse_down_ = false;
  if (ui_) ui_->pointer(event.x, event.y, mouse_down_);
  pointer_moved_ = true;
  const bool tablet = pen_ && pen_->connection() == PenConnection::kConnected;
  if (!session_ || tablet) return;
  if (!mouse_) {
    mouse_ = std::make_unique<MousePen>(display_.width(), display_.height());
    session_->setDevice(mouse_->device(), clockNs());
    session_->setCalibration(CalibrationProfile{}, clockNs());
    if (!pen_connected_once_) {
      pen_connected_once_ = true;
      if (options_.on_first_connection) options_.on_first_connection();
    }
    char text[160];
    std::snprintf(text, sizeof text,
                  "no tablet: the mouse paints with pressure %.2f (-/+ change it; the wheel "
                  "or [ ] the brush size)",
                  double(mouse_->pressure()));
    say(text);
  }
  last_mouse_sample_ns_ = clockNs();
  feedSample(mouse_->sample(event, clockNs()));
}

void PaintScreen::repeatHeldMouse() {
  if (!mouse_ || !mouse_->down() || !session_ || !session_->engine().inStroke()) return;
  const int64_t now = clockNs();
  if (now - last_mouse_sample_ns_ < 50'000'000) return;  // 20 Hz is enough to time 2 s
  last_mouse_sample_ns_ = now;
  feedSample(mouse_->repeat(now));
}

void PaintScreen::updateVacuumCentre(const MappedSample& mapped) {
  if (session_->mode() != Mode::kErase || session_->eraseTool() != EraseTool::kVacuum) return;
  // §3.5.1: the sphere under the pointer: on the pointer's ray, where it meets the canvas's
  // mid-plane; a pen pressed moves it along that ray to the height its pressure gives (the
  // thesis's height from pressure). The mouse has no pressure: the canvas (Canvas mode) sets
  // the height.
  // A mouse sends no samples while it rests, so its 1€-filtered position would stay behind the
  // pointer: the sphere takes the pointer's own pixel (the mouse's units are screen pixels).
  const float x = mouse_ ? float(mapped.raw.x_raw) : float(mapped.preview_x_px);
  const float y = mouse_ ? float(mapped.raw.y_raw) : float(mapped.preview_y_px);
  glm::vec3 origin, dir;
  session_->camera().pixelRay(x, y, display_.width(), display_.height(), &origin, &dir);
  const Volume& v = session_->volume();
  float height = session_->canvas().altitude;
  if (mapped.contact && !mouse_)
    height = v.worldMin().y +
             std::clamp(mapped.pressure, 0.0f, 1.0f) * (v.worldMax().y - v.worldMin().y);
  if (std::abs(dir.y) < 1e-4f) return vacuum_centre_.reset();
  const float t = (height - origin.y) / dir.y;
  if (t <= 0.0f) return vacuum_centre_.reset();
  vacuum_centre_ = origin + t * dir;
}

void PaintScreen::handleEvent(const PenEvent& event, const MappedSample& mapped) {
  const Mode mode = session_->mode();
  const int w = display_.width(), h = display_.height();
  switch (event.kind) {
    case PenEvent::Kind::kButtonDown:
      side_buttons_ |= event.button;
      if (event.button == kPenStylus2) onCommand(Command::kMenu, event.t_ns);  // Appendix A 26
      return;
    case PenEvent::Kind::kButtonUp:
      side_buttons_ &= ~event.button;
      return;
    case PenEvent::Kind::kProximityOut:
      vacuum_centre_.reset();
      return;
    case PenEvent::Kind::kDown:
      drag_start_ = {event.x, event.y};
      if (mode == Mode::kCamera) drag_camera_ = session_->camera();
      if (mode == Mode::kCanvas) drag_canvas_ = session_->canvas();
      if (mode == Mode::kLight) drag_light_ = session_->light();
      [[fallthrough]];
    case PenEvent::Kind::kDrag: {
      const glm::vec2 delta = glm::vec2(event.x, event.y) - drag_start_;
      if (mode == Mode::kCamera && drag_camera_) {
        const Camera& from = session_->camera();
        if (side_buttons_ & kPenStylus1) {
          // Zoom: dragging up moves the eye closer, exponentially in the distance.
          drag_camera_ = from.zoomed(std::exp(delta.y / float(h)));
          drag_move_ = CameraMove::kZoom;
        } else if (pan_drag_) {
          // Pan: the scene follows the pen (the point under it stays under it).
          const float step = from.worldPerPixelAtTarget(h);
          drag_camera_ = from.panned(-delta.x * step, delta.y * step);
          drag_move_ = CameraMove::kPan;
        } else {
          // Orbit: a full screen width turns 180°, a full height 90°.
          drag_camera_ = orbitCamera(from, -180.0f * delta.x / float(w), 90.0f * delta.y / h);
          drag_move_ = CameraMove::kOrbit;
        }
      } else if (mode == Mode::kCanvas && drag_canvas_) {
        // A full screen height moves the canvas across the whole sky box.
        const float height = shownVolume().worldMax().y - shownVolume().worldMin().y;
        Canvas c = session_->canvas();
        c.altitude = std::clamp(c.altitude - delta.y / float(h) * height,
                                shownVolume().worldMin().y, shownVolume().worldMax().y);
        drag_canvas_ = c;
      } else if (mode == Mode::kLight && drag_light_) {
        drag_light_->direction = lightDirectionAt(shownCamera(), event.x, event.y, w, h);
      }
      updateVacuumCentre(mapped);
      return;
    }
    case PenEvent::Kind::kUp:
      if (drag_camera_) apply(ui::SetCamera{*drag_camera_, drag_move_}, event.t_ns);
      if (drag_canvas_)
        apply(ui::SetCanvas{drag_canvas_->altitude, drag_canvas_->thickness}, event.t_ns);
      if (drag_light_) {
        apply(ui::SetLight{drag_light_->direction, drag_light_->colour}, event.t_ns);
        light_release_pending_ = true;
      }
      drag_camera_.reset();
      drag_canvas_.reset();
      drag_light_.reset();
      return;
    case PenEvent::Kind::kHover:
    case PenEvent::Kind::kProximityIn:
      updateVacuumCentre(mapped);
      return;
  }
}

bool PaintScreen::hasPaint() const {
  return session_ && (session_->history().canUndo() || session_->engine().inStroke());
}

std::string PaintScreen::update(const FrameContext& frame) {
  iteration_start_ = std::chrono::steady_clock::now();
  if (replay_view_) {
    menu_open_ = session_->menuOpen();  // as the replay has it; nothing else moves on its own
    return "";
  }
  if (quit_confirmed_) return "q (confirmed)";
  if (toast_until_ns_ != 0 && clockNs() >= toast_until_ns_) {
    toast_until_ns_ = 0;  // one more frame draws the screen without it
    pointer_moved_ = true;
  }
  repeatHeldMouse();
  repeatRestingPen();
  if (!options_.visitor_mode && pen_ && last_connection_ == int(PenConnection::kFinished) &&
      !lit_pending_ && !refine_pending_ && !session_->engine().inStroke())
    return "replay finished";
  if (orbiting_) orbit_degrees_ += options_.orbit_degrees_per_second * float(frame.since_last_s);
  advanceAnimation(frame);
  return "";
}

bool PaintScreen::needsFrame() const {
  if (orbiting_ || !refined_ || lit_pending_ || refine_pending_) return true;
  if (animationPlaying()) return true;
  if (renderer_.lightIsPreview() && !drag_light_) return true;  // the full light is to come
  if (menu_open_ || pointer_moved_ || toast_until_ns_ != 0) return true;  // the UI moves
  if (pen_ && pen_connected_once_) return true;  // the cursor and footprint follow the pen
  return !drawn_ || !(*drawn_ == currentKey());
}

bool PaintScreen::drawLastScene(FrameContext& frame) {
  if (!drawn_ || scene_.width() != frame.width || scene_.height() != frame.height) return false;
  glBlitNamedFramebuffer(scene_.fbo(), frame.display.framebuffer(), 0, 0, frame.width, frame.height,
                         0, 0, frame.width, frame.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  return true;
}

bool PaintScreen::paintingSetUp(std::string* error) {
  if (!overlay_ready_) {
    if (!overlay_.init(error)) return false;
    overlay_.beginFootprint(session_ ? session_->footprintWidth() : display_.width(),
                            session_ ? session_->footprintHeight() : display_.height());
    overlay_ready_ = true;
  }
  if (scene_.width() != display_.width() || scene_.height() != display_.height()) {
    if (!scene_.create(display_.width(), display_.height(), RenderTarget::Format::kRgba8, error))
      return false;
    // Warm-up: the first reduced-resolution render allocates the renderer's smaller target;
    // do that now rather than inside the first pen-up -> lit frame.
    RenderOptions warm_up = options_.render;
    warm_up.scale = moving_scale_;
    warm_up.moving = warm_up.scale < 1.0f;  // the lit frame's program variant, compiled now
    syncShown();
    renderer_.render(shownCamera(), display_.width(), display_.height(), scene_.fbo(), warm_up);
    drawn_.reset();
  }
  return true;
}

void PaintScreen::drawStill(FrameContext& frame, PaintFrameInfo* info) {
  const int w = display_.width(), h = display_.height();
  const auto render_start = std::chrono::steady_clock::now();
  frame_index_ = frame.frame;
  SceneWork work;
  renderScene(&work);
  // Late latching: the ink shows the samples that came while the scene was being cast. A
  // latched lift (or a view the pen changed) makes the scene stale: cast it again. Samples the
  // on-screen UI holds (menu open, pen over a target) are not ink: they wait for the next
  // frame, so the UI sees every press and release in its own frame.
  const bool ui_holds_pen = menu_open_ || pointer_over_ui_ || (session_ && session_->penCaptured());
  if (options_.ink_first && frame.latch_pen && !lit_pending_ && !replay_view_ && !ui_holds_pen) {
    frame.latch_pen();
    if (lit_pending_ || sceneStale()) renderScene(&work);
  }
  if (lit_pending_) {
    // The footprint was just cleared, so the frame is the scene alone: a blit instead of the
    // overlay's full-frame composite (tens of ms on llvmpipe).
    glBlitNamedFramebuffer(scene_.fbo(), display_.framebuffer(), 0, 0, w, h, 0, 0, w, h,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    overlay_.invalidate();
    frame.shows_lift = true;
  } else {
    overlay_.draw(scene_.texture(), display_.framebuffer(), w, h, cursor_);
  }
  info->painting_view = true;
  info->in_stroke = session_ && session_->engine().inStroke();
  info->texels_uploaded = texels_this_frame_;
  texels_this_frame_ = 0;
  if (lit_pending_ || work.refine) glFinish();  // the frame is really drawn, not only queued
  const double since_lift = msSince(lift_time_);
  const double since_lift_sample = msSinceSample(lift_sample_ns_);
  if (lit_pending_) {
    info->first_lit_after_lift = true;
    info->pen_up_to_lit_ms = since_lift;
    info->lift_sample_to_lit_ms = since_lift_sample;
    info->mapping_ms = lift_mapping_ms_;
    info->sync_ms = work.sync_ms;
    info->render_ms = work.render_ms;
    info->composite_ms = msSince(render_start) - work.sync_ms - work.render_ms;
    info->rendered_pixels = work.rendered_pixels;
    info->render_scale = work.render_scale;
    lit_pending_ = false;
    if (work.render_scale >= 1.0f) {  // shown at full resolution at once: nothing to refine
      info->refined_after_lift = true;
      info->pen_up_to_refined_ms = since_lift;
      info->lift_sample_to_refined_ms = since_lift_sample;
    }
  } else if (work.refine) {
    info->refined_after_lift = true;
    info->pen_up_to_refined_ms = since_lift;
    info->lift_sample_to_refined_ms = since_lift_sample;
    info->render_ms = work.render_ms;
    info->rendered_pixels = work.rendered_pixels;
    info->render_scale = work.render_scale;
  }
}

bool PaintScreen::sceneStale() const {
  const SceneKey key = currentKey();
  // A coarse light is swept in full once its release has been shown, or the animation stopped.
  return !drawn_ || !(*drawn_ == key) ||
         (renderer_.lightIsPreview() && !drag_light_ && !light_release_pending_ &&
          !animationPlaying());
}

bool PaintScreen::inkLive() const {
  return options_.ink_first && session_ && !replay_view_ && session_->engine().inStroke();
}

void PaintScreen::renderScene(SceneWork* work) {
  const int w = display_.width(), h = display_.height();
  const auto render_start = std::chrono::steady_clock::now();
  const SceneKey key = currentKey();
  // While the light ball is dragged, and for the first frame at its release, the light is swept
  // at reduced resolution per axis (PaintLoopOptions::light_drag_divisor) and the scene cast at
  // the light drag's scale; the frame after the release sweeps it in full at full resolution.
  const bool light_preview = drag_light_ || light_release_pending_;
  const bool stale = sceneStale();
  // A refinement yields to the ink: while a stroke is drawn it waits (a band of rows would not
  // do: each cast pays the ray bounds and clears of the whole sky, 100+ ms on a loaded llvmpipe).
  // Nor is a coarse light refined: its full sweep comes first.
  const bool refine = refine_pending_ && !stale && !inkLive() && !light_preview;
  work->refine = work->refine || refine;
  if (!stale && !refine) return;
  const bool light_scaled = light_preview && !refine;
  light_drag_frame_ = drag_light_.has_value();
  const SyncStats sync = syncShown();  // the dirty box only (§4)
  const auto synced = std::chrono::steady_clock::now();
  work->sync_ms = std::chrono::duration<double, std::milli>(synced - render_start).count();
  // Right after a lift, and while a drag moves the view or the light, the scene is shown at
  // the moving resolution first, then refined to full resolution.
  RenderOptions options = options_.render;
  options.style = key.style;
  options.collect_stats = show_stats_;
  const bool dragging = drag_camera_ || drag_light_;
  options.scale = light_scaled ? quantisedScale(light_drag_scale_, options_.min_light_drag_scale)
                  : (lit_pending_ || dragging || animationPlaying()) && !refine ? moving_scale_
                                                                                : 1.0f;
  options.moving = options.scale < 1.0f;
  // When only the volume changed (a stroke, erase, undo), only the pixels whose rays cross
  // what the sync rewrote (its dirty box and light box) are re-rendered over the cached scene;
  // a full-resolution frame also redoes what is still at the reduced resolution.
  // A sky grown around the drawn volume, which the renderer followed (VolumeRenderer::sync),
  // shows the same world: only what changed since is re-rendered, as after an edit.
  const uint64_t drawn_volume =
      drawn_ && sync.followed_growth && drawn_->volume == shownVolume().growth().from_instance
          ? key.volume
      : drawn_ ? drawn_->volume
               : 0;
  ScreenRegion region = ScreenRegion::wholeFrame(w, h);
  if (refine)
    region = {};
  else if (drawn_ && options_.region_rerender && !key.stats &&
           SceneKey{drawn_volume, key.generation, drawn_->camera, drawn_->light, drawn_->stats,
                    drawn_->style} == key)
    region = changedScreenRegion(key.camera, w, h, shownVolume(), sync, key.style);
  // Right after a lift, a change the last refinements say can be cast at full resolution
  // within the pen-up budget is shown so at once (no reduced frame, no refinement).
  const bool full_at_once =
      lit_pending_ && !refine && !dragging && !animationPlaying() && liftFitsFullResolution(region);
  if (full_at_once) {
    options.scale = 1.0f;
    options.moving = false;
  }
  if (options.scale >= 1.0f) region = region.unite(unrefined_);
  if (!region.empty()) {
    options.region = region.renderRegion();
    // A drag turning the view: as the orbit's moving frames, full resolution by reprojection
    // where that is the way chosen (the frame at rest, refined below, is a full cast either way).
    if (drag_camera_ && !light_scaled && !refine)
      renderMoving(frame_index_, w, h, options, sync, scene_.fbo());
    else
      renderer_.render(key.camera, w, h, scene_.fbo(), options);
    work->rendered_pixels = renderer_.lastStats().pixels_cast;
    work->render_scale = options.scale;
  }
  unrefined_ = options.scale < 1.0f ? unrefined_.unite(region) : ScreenRegion{};
  if (lit_pending_ || refine) {
    glFinish();
    work->render_ms = msSince(synced);
    if (options.scale >= 1.0f) learnFullResolutionCost(work->render_ms, region);
  }
  overlay_.invalidate();
  drawn_ = key;
  refine_pending_ = !unrefined_.empty();
}

bool PaintScreen::liftFitsFullResolution(const ScreenRegion& region) const {
  if (full_ms_per_pixel_ <= 0.0 || region.empty()) return false;
  const double predicted_ms = full_ms_per_pixel_ * double(region.pixels());
  return msSince(lift_time_) + predicted_ms <= options_.lift_budget_ms;
}

void PaintScreen::learnFullResolutionCost(double render_ms, const ScreenRegion& region) {
  // Regions of a few pixels say little about the cost per pixel (fixed costs dominate).
  if (region.pixels() < 4096) return;
  const double rate = render_ms / double(region.pixels());
  full_ms_per_pixel_ = full_ms_per_pixel_ > 0.0 ? 0.5 * (full_ms_per_pixel_ + rate) : rate;
}

glm::vec2 PaintScreen::lightBallOnScreen() const {
  const Camera camera = shownCamera();
  return project(camera, lightBallRadius(camera) * shownLight().direction, display_.width(),
                 display_.height());
}

bool PaintScreen::drawOverlays(std::string* error) {
  hud_items_ = hudItems();
  if (hud_items_.empty()) return true;
  if (!hud_.init(error)) return false;
  hud_.draw(display_.framebuffer(), display_.width(), display_.height(), hud_items_);
  return true;
}

std::vector<HudItem> PaintScreen::hudItems() const {
  const int w = display_.width(), h = display_.height();
  const bool in_range = (pen_ || replay_view_) && !orbiting_ && cursor_.visible && session_;
  const bool circles = show_circles_ && session_ && !session_->lastCircles().empty();
  std::vector<HudItem> items;
  const Camera camera = shownCamera();
  if (session_) {
    const Mode mode = session_->mode();
    const Volume& volume = shownVolume();
    // Where a stroke can land (§7.7.5 problem 2): the sky as wide as it may grow (a stroke past
    // its edge grows it first). Outside it the screen is veiled while the pen is in range, so
    // ink that cannot land looks different at once; in Canvas mode the outline follows the
    // canvas as it moves.
    const Canvas canvas = drag_canvas_ ? *drag_canvas_ : session_->canvas();
    if ((in_range && (mode == Mode::kPaint || mode == Mode::kErase)) || mode == Mode::kCanvas) {
      const SkyExtent reach = session_->reachableSky();
      const DrawableRegion region(camera, canvas, reach.worldMin(), reach.worldMax(), w, h);
      if (mode == Mode::kPaint) appendOutsideVeil(region, &items);
      // The canvas as a grid on its mid-plane (thesis Fig. 3.4) across that reach, every eighth
      // of the home box (the thesis's sky box).
      const auto to_screen = [&](glm::vec3 p) { return project(camera, p, w, h); };
      appendCanvasGrid(canvas, reach.worldMin(), reach.worldMax(), 8 * reach.span, to_screen,
                       &items);
      appendCanvasOutline(region.outline(), &items);
    }
    if (mode == Mode::kErase && vacuum_centre_) {
      // §3.5.1 Fig. 3.5: the sphere, and a rod from the canvas up or down to it.
      const float radius = 0.5f * session_->eraseDiameter(EraseTool::kVacuum);
      const glm::vec2 c = project(camera, *vacuum_centre_, w, h);
      const glm::vec2 edge = project(
          camera,
          *vacuum_centre_ +
              radius * glm::normalize(glm::cross(camera.eye - *vacuum_centre_, glm::vec3(0, 1, 0)) +
                                      glm::vec3(1e-6f)),
          w, h);
      const glm::vec3 foot(vacuum_centre_->x, session_->canvas().altitude, vacuum_centre_->z);
      // §3.5.1: grids on the three axis-aligned planes through the sphere's centre.
      // ... across a home box's width (2 world units) around the sphere, moved inside the sky:
      // the whole sky box when the sky is one box.
      const glm::vec3 grid_min(
          std::clamp(vacuum_centre_->x - 1.0f, volume.worldMin().x, volume.worldMax().x - 2.0f),
          volume.worldMin().y,
          std::clamp(vacuum_centre_->z - 1.0f, volume.worldMin().z, volume.worldMax().z - 2.0f));
      appendAxisPlaneGrids(
          *vacuum_centre_, grid_min,
          glm::vec3(grid_min.x + 2.0f, volume.worldMax().y, grid_min.z + 2.0f), 4,
          [&](glm::vec3 p) { return project(camera, p, w, h); }, &items);
      items.push_back(makeHudRing(c, glm::length(edge - c), 2.0f, {1.0f, 0.55f, 0.2f, 0.9f}));
      items.push_back(
          makeHudSegment(project(camera, foot, w, h), c, 2.0f, {0.8f, 0.8f, 0.85f, 0.9f}));
    }
    if (mode == Mode::kLight) {
      // The light ball on its sphere about the scene origin, and the line to the origin.
      const glm::vec3 ball = lightBallRadius(camera) * shownLight().direction;
      const glm::vec2 b = project(camera, ball, w, h);
      items.push_back(makeHudSegment(project(camera, glm::vec3(0.0f), w, h), b, 2.0f,
                                     {1.0f, 0.9f, 0.5f, 0.7f}));
      items.push_back(makeHudRing(b, 14.0f, 5.0f, glm::vec4(shownLight().colour, 1.0f)));
    }
  }
  if (circles)
    appendCircleRings(session_->lastCircles(), session_->footprintWidth(),
                      session_->footprintHeight(), w, h, &items);
  if (show_stats_) appendStatsPanel(renderer_.lastStats(), w, h, &items);
  return items;
}

bool PaintScreen::draw(FrameContext& frame, std::string* error) {
  PaintFrameInfo info;
  info.frame = frame.frame;
  if (!drawPass(frame, &info, error)) return false;
  if (lateInkApplies(frame, info) && !drawLateInk(frame, &info, error)) return false;
  noteFrame(info);
  last_info_ = info;
  if (options_.on_frame) options_.on_frame(info);
  return true;
}

bool PaintScreen::drawPass(FrameContext& frame, PaintFrameInfo* info, std::string* error) {
  if ((pen_ || replay_view_) && !orbiting_) {
    if (!paintingSetUp(error)) return false;
    drawStill(frame, info);
  } else {
    const SyncStats sync = syncShown();
    RenderOptions render_options = options_.render;
    render_options.style = currentStyle();
    const bool moving = orbiting_ || animationPlaying();
    render_options.moving = moving;
    // Quantised to 1/20 so the renderer's reduced-size target is not reallocated every frame.
    render_options.scale = moving ? orbitRenderScale(moving_scale_, options_) : 1.0f;
    render_options.collect_stats = (!orbiting_ && options_.print_stats) || show_stats_;
    glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
    if (moving)
      renderMoving(frame.frame, frame.width, frame.height, render_options, sync,
                   display_.framebuffer());
    else
      renderer_.render(shownCamera(), frame.width, frame.height, display_.framebuffer(),
                       render_options);
    if (!moving) {
      refined_ = true;
      ++refined_frames_;
      drawn_ = currentKey();
      if (options_.print_stats) std::printf("%s\n", renderer_.lastStats().summary().c_str());
    }
  }
  if (!drawOverlays(error)) return false;
  drawUi(frame);
  return true;
}

void PaintScreen::noteFrame(const PaintFrameInfo& info) {
  if (!info.painting_view) return;
  if (info.first_lit_after_lift && info.lift_sample_to_lit_ms > 0.0)
    lift_sample_to_lit_ms_.push_back(info.lift_sample_to_lit_ms);
  if (info.refined_after_lift && info.lift_sample_to_refined_ms > 0.0)
    lift_sample_to_refined_ms_.push_back(info.lift_sample_to_refined_ms);
  if (info.first_lit_after_lift) {
    pen_up_to_lit_ms_.push_back(info.pen_up_to_lit_ms);
    mapping_ms_.push_back(info.mapping_ms);
    sync_ms_.push_back(info.sync_ms);
    render_ms_.push_back(info.render_ms);
    if (options_.print_stats)
      std::printf(
          "stroke %ld: pen-up -> lit frame %.1f ms (mapping %.1f, sync %.1f, render "
          "%.1f, composite %.1f)\n",
          strokes_seen_ - 1, info.pen_up_to_lit_ms, info.mapping_ms, info.sync_ms, info.render_ms,
          info.composite_ms);
  }
  if (info.refined_after_lift) {
    refined_ms_.push_back(info.pen_up_to_refined_ms);
    if (options_.print_stats)
      std::printf("stroke %ld: pen-up -> full-resolution lit frame %.1f ms\n", strokes_seen_ - 1,
                  info.pen_up_to_refined_ms);
  }
}

void PaintScreen::presented(const FrameContext& frame, double frame_ms) {
  // Every presented frame's timing goes to the session's journal (a replay draws, not records).
  if (frame.record && session_ && !replay_view_) session_->journalFrame(*frame.record);
  const PaintFrameInfo& info = last_info_;
  light_release_pending_ = false;  // the release's frame is shown
  if (moving_frame_drawn_) {
    // The moving frame's own time (its update to its present), not the wait for the next move.
    const MovingFrameDrawn drawn = *moving_frame_drawn_;
    moving_path_[drawn.kind].measured(drawn.reprojected, msSince(iteration_start_));
    ++moving_frames_[drawn.reprojected ? 1 : 0];
    moving_frame_drawn_.reset();
  } else {
    for (MovingPathChooser& chooser : moving_path_) chooser.rested();
  }
  if (info.painting_view && light_drag_frame_) {
    // The drag frame's own time (its update to its present), not the wait for the next move.
    light_drag_scale_ = nextLightDragScale(light_drag_scale_, msSince(iteration_start_), options_);
    light_drag_frame_ = false;
  }
  if (info.painting_view) {
    // Frames while a stroke is drawn, except the lift frames (mapping + re-render).
    if (info.in_stroke && !info.first_lit_after_lift && !info.refined_after_lift)
      painting_frame_ms_.push_back(frame_ms);
    return;
  }
  if (orbiting_ && frame.frame > 0) {
    moving_frame_ms_.push_back(frame_ms);
    // Keep the orbit fluid: shrink the resolution when a frame is over budget, grow it back
    // when there is room (≥ 30 fps at scale ≥ 0.5 is the target).
    moving_scale_ = nextMovingScale(moving_scale_, frame_ms, options_);
  }
}

void PaintScreen::drawUi(const FrameContext& frame) {
  if (ui_failed_) return;
  if (!ui_) {
    ui_ = std::make_unique<UiOverlay>();
    ui_->addGlyphs(visitor_glyphs_);
    std::string error;
    if (!ui_->init(&error)) {
      say("on-screen UI unavailable (keys still work): " + error);
      ui_.reset();
      ui_failed_ = true;
      return;
    }
  }
  UiOverlayState state;
  state.status = show_stats_ ? detailLine() : statusLine();
  state.notice = notice_;
  state.toast = toast();
  state.hint = hint();
  state.message_width = options_.message_area * float(frame.width);
  if (!state.hint.empty() && options_.message_bottom)
    state.message_bottom = options_.message_bottom(frame.width, frame.height);
  if (help_open_) state.help = helpSections(options_.visitor_mode);
  if (show_stats_) appendStatsLabels(frame.width, frame.height, &state.labels);
  // A morph or wind shown says what it is and how to apply or leave it.
  if (notice_.empty() && animation_ && animation_->active()) state.notice = animation_->status();
  state.menu_open = menu_open_;
  state.mode = session_ ? int(session_->mode()) : 2;
  state.can_undo = session_ && session_->history().canUndo();
  state.can_redo = session_ && session_->history().canRedo();
  state.visitor = options_.visitor_mode;
  state.animation = animation_ && animation_->active();
  if (visitorWords()) {
    // Only the kiosk's words: its status line, menu and help, the edge-on warning as its text.
    const Mode mode = session_ ? session_->mode() : Mode::kPaint;
    state.status = visitorStatus(mode, visitor_text_);
    state.notice = notice_.empty() ? "" : visitor_text_("edge_on");
    state.help.clear();
    state.labels.clear();
    state.visitor_words = UiOverlayState::VisitorWords{
        visitor_text_("menu_button"), visitor_text_("menu_close"), visitorMenu(mode, visitor_text_),
        help_open_ ? visitorHelp(visitor_text_) : std::vector<std::string>{}};
  }
  glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
  glViewport(0, 0, frame.width, frame.height);
  const std::vector<Command> tapped =
      ui_->draw(frame.width, frame.height, frame.since_last_s, state);
  pointer_over_ui_ = ui_->pointerOverUi();
  pointer_moved_ = false;
  if (replay_view_) return;  // a replay's taps are in its journal already
  for (Command command : tapped) {
    tapped_.push_back(command);
    onCommand(command, frame.now_ns);
    if (command != Command::kMenu && menu_open_)
      setMenu(false, frame.now_ns);  // a choice closes it
  }
}

void PaintScreen::appendStatsLabels(int w, int h, std::vector<UiLabel>* labels) const {
  // The words of the statistics panel's rows (hud_items.cpp appendStatsPanel: three rows of
  // 18 px from text_top, digits from left + 15 px; the bars below).
  const RenderStats& stats = renderer_.lastStats();
  if (!stats.has_samples || stats.histogram.empty()) return;
  const StatsPanelLayout layout = statsPanelLayout(w, h);
  const int line = 18, text_top = layout.baseline_y - layout.max_height - 3 * line - 8;
  const Bilingual rows[3] = {msg::kStatsTotal, msg::kStatsMean, msg::kStatsMax};
  const float x = float(layout.left + int(stats.histogram.size()) * layout.bar_pitch + 24);
  for (int r = 0; r < 3; ++r)
    labels->push_back({x, float(text_top + r * line - 3), rows[r].oneLine(), 18.0f});
  labels->push_back({x, float(layout.baseline_y - 24), msg::kStatsHistogram.oneLine(), 18.0f});
}

std::vector<std::string> PaintScreen::hint() const {
  if (!session_) return {msg::kNoSession.en, msg::kNoSession.zh};
  if (options_.visitor_mode) return {};  // the kiosk's own texts invite (kiosk/texts.toml)
  // Until the first stroke (a camera or mode change is not one); a cloud opened or resumed
  // needs no invitation either.
  if (session_->strokesMapped() > 0 || session_->engine().inStroke() ||
      session_->volume().allocatedBricks() > 0)
    return {};
  return firstScreenHint(session_->mode() == Mode::kPaint,
                         pen_ && pen_->connection() == PenConnection::kConnected);
}

std::string PaintScreen::statusLine() const {
  if (!session_) return msg::kNoSession.oneLine();
  const PaintSession& s = *session_;
  const Bilingual mode = modeLabel(s.mode());
  std::string line = std::string(mode.en) + " " + mode.zh;
  char text[160];
  switch (s.mode()) {
    case Mode::kCamera:
      line += orbiting_   ? " · auto-rotating (Space stops)"
              : pan_drag_ ? " · drag pans (P: orbit)"
                          : " · drag turns the view";
      break;
    case Mode::kCanvas: {
      const Volume& v = s.volume();
      std::snprintf(text, sizeof text, " · altitude %d · thickness %.2f",
                    int(std::lround((s.canvas().altitude - v.worldMin().y) / v.voxelSize().y)),
                    double(s.canvas().thickness));
      line += text;
      break;
    }
    case Mode::kPaint:
      std::snprintf(text, sizeof text, " · brush %s · size %.2f ([ ]%s)",
                    brushKindName(s.selectedBrush()), double(s.brushSize()),
                    mouse_ ? ", wheel" : "");
      line += text;
      break;
    case Mode::kErase:
      std::snprintf(text, sizeof text, " · %s · size %.2f", eraseToolName(s.eraseTool()),
                    double(s.eraseDiameter(s.eraseTool())));
      line += text;
      break;
    case Mode::kLight:
      line += " · drag the light ball";
      break;
  }
  if (s.mode() != Mode::kCamera && orbiting_) line += " · auto-rotating (Space in Camera mode)";
  if (s.engine().inStroke()) line += " · lift to make the cloud";
  const bool tablet = pen_ && pen_->connection() == PenConnection::kConnected;
  if (tipOnlyPen())
    line += " · pen without pressure: strokes at " +
            std::to_string(tip_only_pressure_).substr(0, 4) + " (-/+), erase: 4 or Menu";
  else if (tablet)
    line += std::strcmp(pen_->backendName(), "replay") == 0 ? " · recorded pen (replay)" : " · pen";
  else if (pen_ || mouse_)
    line += " · mouse, pressure " + std::to_string(mouse_ ? mouse_->pressure() : 0.6f).substr(0, 4);
  return line + " · H help";
}

std::string PaintScreen::detailLine() const {
  if (!session_) return "no tablet: the bundled cloud orbits; connect a pen to paint";
  const PaintSession& s = *session_;
  char text[256];
  const Volume& v = s.volume();
  const int altitude_voxels =
      int(std::lround((s.canvas().altitude - v.worldMin().y) / v.voxelSize().y));
  std::snprintf(text, sizeof text,
                "%s mode | brush %s | mapping %s | canvas altitude %d thickness %.2f | %s style",
                modeName(s.mode()), brushKindName(s.selectedBrush()), toString(s.mappingMethod()),
                altitude_voxels, double(s.canvas().thickness), renderStyleName(currentStyle()));
  std::string line = text;
  if (s.mode() == Mode::kPaint) {
    std::snprintf(text, sizeof text, " | size %.2f ([ ]%s)", double(s.brushSize()),
                  mouse_ ? ", wheel" : "");
    line += text;
  }
  if (s.mode() == Mode::kErase) {
    std::snprintf(text, sizeof text, " | %s %.2f", eraseToolName(s.eraseTool()),
                  double(s.eraseDiameter(s.eraseTool())));
    line += text;
  }
  if (s.mode() == Mode::kPaint || s.mode() == Mode::kCanvas) {
    // Where a stroke can land: the veil's edge is the sky's widest extent.
    const glm::ivec3 now = s.sky().dims(), reach = s.reachableSky().dims();
    // A journal of specification 1.4 or older replays its placed pictures and models clipped:
    // its sky grows with strokes only.
    if (reach.x > now.x)
      std::snprintf(text, sizeof text, " | sky %dx%d voxels, grows to %dx%d as you paint%s", now.x,
                    now.z, reach.x, reach.z, s.settings().placementsGrowSky() ? "" : " strokes");
    else
      std::snprintf(
          text, sizeof text, " | sky %dx%d voxels, %s: ink in the veil %s", now.x, now.z,
          s.settings().sky_max_span > s.settings().sky_span ? "as wide as it can grow" : "fixed",
          s.settings().veil_ink_left_out ? "is left out" : "lands off the canvas");
    line += text;
  }
  if (s.mode() == Mode::kCamera && pan_drag_) line += " | drag pans (P: orbit)";
  if (s.engine().inStroke()) line += " | stroke open: lift the pen to make the cloud";
  if (mouse_ && !(pen_ && pen_->connection() == PenConnection::kConnected))
    line += " | mouse as pen, pressure " + std::to_string(mouse_->pressure()).substr(0, 4);
  else if (pen_ && pen_->connection() != PenConnection::kConnected &&
           pen_->connection() != PenConnection::kFinished)
    line += std::string(" | no tablet yet: plug one in (") + pen_->statusMessage() + ")";
  else if (pen_samples_ == 0)
    line += " | waiting for the pen: bring it near the tablet";
  if (tipOnlyPen())
    line += " | pen without pressure: strokes at " +
            std::to_string(tip_only_pressure_).substr(0, 4) + " (-/+), erase: 4 or Menu";
  return line;
}

void PaintScreen::finish(PaintLoopSummary* summary) const {
  summary->pen_samples = pen_samples_;
  summary->strokes_mapped = strokes_seen_;
  summary->pen_up_to_lit_ms = pen_up_to_lit_ms_;
  summary->mapping_ms = mapping_ms_;
  summary->sync_ms = sync_ms_;
  summary->render_ms = render_ms_;
  summary->pen_up_to_refined_ms = refined_ms_;
  summary->lift_sample_to_lit_ms = lift_sample_to_lit_ms_;
  summary->lift_sample_to_refined_ms = lift_sample_to_refined_ms_;
  summary->refined_frames = refined_frames_;
  summary->final_moving_scale = moving_scale_;
  summary->reduced_moving_frames = moving_frames_[0];
  summary->reprojected_moving_frames = moving_frames_[1];
  summary->median_painting_frame_ms = medianOf(painting_frame_ms_);
  summary->painting_frames = long(painting_frame_ms_.size());
  summary->median_frame_ms = medianOf(moving_frame_ms_);
}

}  // namespace cb
