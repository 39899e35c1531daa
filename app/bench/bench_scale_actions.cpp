#include "app/bench/bench_scale_actions.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "app/bench/bench_report.h"
#include "app/render/gl/display_platforms.h"
#include "app/render/gl/gl.h"
#include "app/render/image_io.h"
#include "app/session/paint_session.h"
#include "app/shell/painter/animation_preview.h"
#include "app/shell/painter/paint_loop.h"
#include "app/shell/painter/paint_screen.h"
#include "app/tools/procedural_mesh.h"
#include "drivers/core/no_pen_source.h"

namespace cb {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kDrags = 3;         // light drags, each released once
constexpr int kDragFrames = 12;   // frames of each drag that move the light
constexpr int kWindFrames = 16;   // wind frames timed (after the first few)
constexpr int kOrbitFrames = 16;  // frames of the Camera-mode drag that turn the view

// The bench tools' silhouette: six overlapping dark discs on white (a cumulus's outline).
ImageRgba8 silhouette(int w, int h) {
  struct Disc {
    float x, y, r;
  };
  const Disc discs[] = {{0.30f, 0.62f, 0.20f}, {0.50f, 0.45f, 0.28f}, {0.70f, 0.60f, 0.20f},
                        {0.40f, 0.70f, 0.16f}, {0.62f, 0.72f, 0.15f}, {0.82f, 0.70f, 0.10f}};
  ImageRgba8 image;
  image.width = w;
  image.height = h;
  image.pixels.assign(size_t(w) * h * 4, 255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (const Disc& d : discs) {
        const float dx = x + 0.5f - d.x * w, dy = y + 0.5f - d.y * h,
                    r = d.r * float(std::min(w, h));
        if (dx * dx + dy * dy <= r * r) {
          uint8_t* p = &image.pixels[(size_t(y) * w + x) * 4];
          p[0] = p[1] = p[2] = 20;
        }
      }
  return image;
}

// The script, run from the painter's on_frame (after a frame is drawn, before it is shown):
// stage by stage, each act injected as the mouse or keyboard would, and the frames timed to
// glFinish.
struct Script {
  Script(Display& d, PaintSession& s) : display(d), session(s) {}
  Display& display;
  PaintSession& session;
  const PaintScreen* screen = nullptr;
  int w = 0, h = 0;
  std::string picture, model;
  std::atomic<bool> stop{false};
  int stage = 0, n = 0, drag = 0;
  Clock::time_point last{}, act{};
  double last_cpu = 0, act_cpu = 0;  // process CPU (all threads) at the last frame, at the act
  std::vector<double> drag_ms, release_ms, release_full_ms, picture_ms, model_ms, wind_ms;
  std::vector<double> drag_cpu, release_cpu, wind_cpu;
  std::vector<double> orbit_ms, orbit_cpu;  // the Camera-mode drag
  // A mouse move of a drag and the present that shows it: the move, injected while frame k is
  // drawn (k − 1 presents so far, FrameTimingRing::total()), is read by frame k + 1's update, so
  // present k + 1 shows it (presents count from 1).
  struct Move {
    uint64_t at_ns = 0, present = 0;
  };
  std::vector<Move> drag_moves, orbit_moves;        // not yet on screen
  std::vector<double> drag_seen_ms, orbit_seen_ms;  // mouse move -> the frame showing it shown
  std::string problem;
  int wind_stopped_at = -1;     // the frame W stopped the wind at
  const char* shots = nullptr;  // a folder for the first drag's and the wind's frames as PNG

  void pointer(DisplayEvent::Kind kind, float x, float y) {
    display.injectEvent(DisplayEvent::pointer(kind, x, y));
  }
  // A drag's mouse move, timed from now to the present that shows it (seen()).
  void move(float x, float y, std::vector<Move>* moves) {
    moves->push_back({monotonicNowNs(), display.frameTimings().total() + 2});
    pointer(DisplayEvent::Kind::PointerMove, x, y);
  }
  // The moves whose present is now in the display's frame timings, into `seen` (ms).
  void seen(std::vector<Move>* moves, std::vector<double>* seen_ms) {
    const FrameTimingRing& timings = display.frameTimings();
    std::erase_if(*moves, [&](const Move& m) {
      for (size_t i = 0; i < timings.size(); ++i)
        if (timings.at(i).frame == m.present) {
          seen_ms->push_back(double(timings.at(i).shown_ns - m.at_ns) / 1e6);
          return true;
        }
      return false;
    });
  }
  void next() {
    ++stage;
    n = 0;
  }
  // The mouse along an arc over the cloud, drag frame i of kDragFrames.
  glm::vec2 dragPoint(int i) const {
    const float a = float(i) / float(kDragFrames) + 0.3f * float(drag);
    return {w * (0.5f + 0.2f * std::cos(3.0f * a)), h * (0.3f + 0.1f * std::sin(3.0f * a))};
  }
  void place(bool is_model) {
    act = Clock::now();
    act_cpu = processCpuMs();
    std::string error;
    if (!session.apply(ui::PlaceShape{is_model, is_model ? model : picture}, 0, &error))
      problem = error;
  }
  void onFrame();
};

void Script::onFrame() {
  glFinish();
  const Clock::time_point now = Clock::now();
  const double frame_ms = std::chrono::duration<double, std::milli>(now - last).count();
  const double act_ms = std::chrono::duration<double, std::milli>(now - act).count();
  const double cpu = processCpuMs(), frame_cpu = cpu - last_cpu;
  last = now;
  last_cpu = cpu;
  ++n;
  seen(&drag_moves, &drag_seen_ms);
  seen(&orbit_moves, &orbit_seen_ms);
  switch (stage) {
    case 0:  // the starting view drawn; Light mode
      if (n == 3) display.injectEvent(DisplayEvent::key('5')), next();
      break;
    case 1: {  // drag the light ball, release, again
      if (n == 1 && session.mode() != Mode::kLight) problem = "the painter is not in Light mode";
      const glm::vec2 p = dragPoint(n);
      if (n == 1) pointer(DisplayEvent::Kind::PointerMove, p.x, p.y);
      if (n == 1) pointer(DisplayEvent::Kind::PointerDown, p.x, p.y);
      if (n >= 3 && n <= kDragFrames + 1)
        drag_ms.push_back(frame_ms), drag_cpu.push_back(frame_cpu);
      if (n >= 2 && n <= kDragFrames) move(p.x, p.y, &drag_moves);
      if (n == kDragFrames + 1) {
        pointer(DisplayEvent::Kind::PointerUp, p.x, p.y);
        act = now;
        act_cpu = cpu;
      }
      if (n == kDragFrames + 2) release_ms.push_back(act_ms), release_cpu.push_back(cpu - act_cpu);
      if (n == kDragFrames + 3) release_full_ms.push_back(act_ms);
      // What a person sees of the first drag (the readback is timed into the next frame).
      if (shots && drag == 0 &&
          (n == 2 || n == 7 || n == kDragFrames || n == kDragFrames + 2 || n == kDragFrames + 3))
        writePng(std::string(shots) + "/light_drag_" + std::to_string(n) + ".png",
                 readFramebufferRgba8(display.framebuffer(), w, h));
      if (n == kDragFrames + 4) ++drag < kDrags ? void(n = 0) : next();
      break;
    }
    case 2:  // a picture placed, then a model
      if (n == 1) place(false);
      if (n == 2) picture_ms.push_back(act_ms);
      if (n == 4) place(true);
      if (n == 5) model_ms.push_back(act_ms);
      if (n == 7) next();
      break;
    case 3: {  // the wind
      if (n == 1) display.injectEvent(DisplayEvent::key('w'));
      const AnimationPreview* a = screen ? screen->animation() : nullptr;
      const bool blowing = a && a->playing();
      if (n >= 5 && blowing) wind_ms.push_back(frame_ms), wind_cpu.push_back(frame_cpu);
      if (n > 4 && !blowing && wind_stopped_at < 0) problem = "the wind does not blow";
      // What a person sees while it blows (the readback is timed into the next frame).
      if (shots && blowing && (n == 6 || n == 12 || n == 19))
        writePng(std::string(shots) + "/wind_" + std::to_string(n) + ".png",
                 readFramebufferRgba8(display.framebuffer(), w, h));
      if (int(wind_ms.size()) >= kWindFrames && wind_stopped_at < 0) {
        display.injectEvent(DisplayEvent::key('w'));  // stopped: the frame at rest, lit in full
        wind_stopped_at = n;
      }
      const bool rested = wind_stopped_at >= 0 && n == wind_stopped_at + 4;
      if (shots && rested)
        writePng(std::string(shots) + "/wind_stopped.png",
                 readFramebufferRgba8(display.framebuffer(), w, h));
      if (rested || !problem.empty()) {
        display.injectEvent(DisplayEvent::key('x'));
        next();
      }
      break;
    }
    case 4: {  // Camera mode (1): the view turned by dragging across the cloud, then let go
      if (n == 1) display.injectEvent(DisplayEvent::key('1'));
      if (n == 3 && session.mode() != Mode::kCamera) problem = "the painter is not in Camera mode";
      const float x = w * (0.35f + 0.015f * float(n)), y = h * 0.5f;
      if (n == 3) pointer(DisplayEvent::Kind::PointerMove, x, y);
      if (n == 3) pointer(DisplayEvent::Kind::PointerDown, x, y);
      if (n >= 4 && n < 4 + kOrbitFrames) move(x, y, &orbit_moves);
      if (n >= 6 && n < 5 + kOrbitFrames)
        orbit_ms.push_back(frame_ms), orbit_cpu.push_back(frame_cpu);
      if (shots && n == 12)
        writePng(std::string(shots) + "/camera_drag_" + std::to_string(n) + ".png",
                 readFramebufferRgba8(display.framebuffer(), w, h));
      if (n == 4 + kOrbitFrames) pointer(DisplayEvent::Kind::PointerUp, x, y);
      if (n == 8 + kOrbitFrames) next();
      break;
    }
    default:
      stop = true;
  }
  if (!problem.empty()) stop = true;
}

double fps(const std::vector<double>& frame_ms) {
  return frame_ms.empty() ? -1.0 : 1000.0 / median(frame_ms);
}

}  // namespace

PainterActionFigures measurePainterActions(Display& display, VolumeRenderer& renderer,
                                           const Volume& cumulus, int width, int height,
                                           const SkyExtent& sky, const std::string& dir,
                                           bool baseline) {
  PainterActionFigures fig;
  PaintSessionSettings settings{width, height, sky.grid};
  settings.sky_span = settings.sky_max_span = sky.span;
  PaintSession session(settings, BrushConfig{}, MappingConfig{});
  session.setQuietMapping(true);
  std::string error;
  if (!session.replaceVolume(cumulus, 0, "bundled cumulus", &error)) {
    std::printf("  painter actions: %s\n", error.c_str());
    return fig;
  }
  Script script(display, session);
  script.w = width;
  script.h = height;
  if (!baseline) script.shots = std::getenv("CLOUDBRUSH_BENCH_SHOTS");
  script.picture = dir + "/silhouette.png";
  script.model = dir + "/torus.obj";
  writePng(script.picture, silhouette(512, 512));
  writeObj(script.model, makeDisplacedTorus(0.6f, 0.25f, 0.2f, 192, 184));

  PaintLoopOptions options;
  options.max_frames = 400;  // a bound for a script that stalls
  options.config_dir = dir + "/config";
  options.state_dir = dir + "/state";
  if (baseline) {
    options.light_drag_divisor = 1;       // the light volume swept in full every drag frame
    options.animation_light_divisor = 1;  // and every wind frame's change
    options.min_light_drag_scale = options.moving_scale;  // and cast at the moving scale
    options.region_rerender = false;
    options.cast_at_volume_detail = false;           // a ray per pixel at rest
    options.moving_frames = MovingFrames::kReduced;  // the moving scale, as the painter had
  }
  options.on_frame = [&](const PaintFrameInfo&) { script.onFrame(); };
  NoPenSource no_tablet;
  PaintLoop loop(display, renderer, cumulus, Light{}, options);
  loop.attachPen(&no_tablet, &session);
  script.screen = &loop.screen();
  PaintLoopSummary summary;
  if (!loop.run(&script.stop, &summary, &error)) {
    std::printf("  painter actions: %s\n", error.c_str());
    return fig;
  }
  if (!script.problem.empty() || script.stage < 5)
    std::printf("  painter actions: the script stopped at stage %d: %s\n", script.stage,
                script.problem.empty() ? "frame limit" : script.problem.c_str());
  fig.light_drag_fps = fps(script.drag_ms);
  fig.light_release_ms = script.release_ms.empty() ? -1 : median(script.release_ms);
  fig.light_release_full_ms = script.release_full_ms.empty() ? -1 : median(script.release_full_ms);
  fig.place_picture_ms = script.picture_ms.empty() ? -1 : median(script.picture_ms);
  fig.place_model_ms = script.model_ms.empty() ? -1 : median(script.model_ms);
  fig.wind_fps = fps(script.wind_ms);
  fig.camera_drag_fps = fps(script.orbit_ms);
  const auto med = [](const std::vector<double>& v) { return v.empty() ? -1.0 : median(v); };
  script.seen(&script.drag_moves, &script.drag_seen_ms);
  script.seen(&script.orbit_moves, &script.orbit_seen_ms);
  fig.light_drag_seen_ms = med(script.drag_seen_ms);
  fig.camera_drag_seen_ms = med(script.orbit_seen_ms);
  fig.light_drag_cpu_ms = med(script.drag_cpu);
  fig.light_release_cpu_ms = med(script.release_cpu);
  fig.wind_cpu_ms = med(script.wind_cpu);
  fig.camera_drag_cpu_ms = med(script.orbit_cpu);
  fig.moving_reprojected = summary.reprojected_moving_frames;
  fig.moving_reduced = summary.reduced_moving_frames;
  fig.drag_frames = int(script.drag_ms.size());
  fig.wind_frames = int(script.wind_ms.size());
  return fig;
}

}  // namespace cb
