#include "app/cli/paint_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>
#include <vector>

#include "app/ui/hud_items.h"
#include "app/ui/paint_session.h"
#include "calibration/profile_store.h"
#include "drivers/core/pen_source.h"

namespace cb {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int64_t monotonicNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double medianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
  return values[values.size() / 2];
}

}  // namespace

double PaintLoopSummary::median_pen_up_to_lit_ms() const {
  return medianOf(pen_up_to_lit_ms);
}

const Volume& PaintLoop::shownVolume() const {
  return pen_connected_once_ ? session_->volume() : volume_;
}

void PaintLoop::attachPen(PenSource* pen, PaintSession* session) {
  pen_ = pen;
  session_ = session;
}

bool PaintLoop::paintingSetUp(std::string* error) {
  if (!overlay_ready_) {
    if (!overlay_.init(error)) return false;
    overlay_.beginFootprint(session_->footprintWidth(), session_->footprintHeight());
    overlay_ready_ = true;
  }
  if (scene_.width() != display_.width() || scene_.height() != display_.height()) {
    if (!scene_.create(display_.width(), display_.height(), RenderTarget::Format::kRgba8, error))
      return false;
    // Warm-up: the first reduced-resolution render allocates the renderer's smaller target;
    // do that now rather than inside the first pen-up -> lit frame.
    RenderOptions warm_up;
    warm_up.scale = std::clamp(options_.moving_scale, options_.min_moving_scale, 1.0f);
    renderer_.sync(shownVolume(), light_);
    renderer_.render(session_->camera(), display_.width(), display_.height(), scene_.fbo(),
                     warm_up);
    scene_stale_ = true;
  }
  return true;
}

void PaintLoop::handlePen(PaintLoopSummary* summary) {
  samples_.clear();
  pen_->poll(0, samples_);
  const int connection = int(pen_->connection());
  const auto select_calibration = [&](uint64_t tool_serial) {
    const PenDeviceInfo& device = pen_->deviceInfo();
    session_->setDevice(device, monotonicNowNs());
    ProfileSelection selection =
        selectProfile(device, tool_serial, options_.config_dir, options_.state_dir);
    for (const std::string& message : selection.messages)
      std::fprintf(stderr, "cloudbrush: calibration: %s\n", message.c_str());
    std::fprintf(stderr, "cloudbrush: calibration from %s\n", selection.source.c_str());
    session_->setCalibration(selection.profile, monotonicNowNs());
  };
  if (connection != last_connection_) {
    last_connection_ = connection;
    const std::string status = pen_->statusMessage();
    std::fprintf(stderr, "cloudbrush: pen %s (%s)%s%s\n", penConnectionName(pen_->connection()),
                 pen_->backendName(), status.empty() ? "" : ": ", status.c_str());
    if (pen_->connection() == PenConnection::kConnected) {
      if (!pen_connected_once_) {
        pen_connected_once_ = true;  // from now on the session's volume is shown and painted
        scene_stale_ = true;
        refined_ = false;
        if (options_.on_first_connection) options_.on_first_connection();
      }
      select_calibration(tool_serial_);
    }
  }
  std::string error;
  for (const PenSample& sample : samples_) {
    if (sample.tool_serial != 0 && sample.tool_serial != tool_serial_) {
      tool_serial_ = sample.tool_serial;  // a profile may be for one tool: select again
      select_calibration(tool_serial_);
    }
    if (sample.in_proximity && orbiting_) {
      orbiting_ = false;  // painting needs a still camera (§3.3)
      refined_ = false;
    }
    if (!orbiting_ && session_->cameraOrbitDegrees() != orbit_degrees_) {
      char text[64];
      std::snprintf(text, sizeof text, "camera_orbit=%.9g", double(orbit_degrees_));
      if (!session_->applyUi(text, sample.t_ns, &error))
        std::fprintf(stderr, "cloudbrush: %s\n", error.c_str());
      scene_stale_ = true;
    }
    const auto received = std::chrono::steady_clock::now();
    const SampleOutcome outcome = session_->feed(sample);
    ++summary->pen_samples;
    if (outcome.stroke_began)
      overlay_.beginFootprint(session_->footprintWidth(), session_->footprintHeight());
    if (!outcome.changed.empty())
      texels_this_frame_ += overlay_.upload(session_->engine().footprint(), outcome.changed);
    if (outcome.stroke_mapped) {
      ++summary->strokes_mapped;
      lift_time_ = received;
      lift_mapping_ms_ = outcome.mapping.timings.total_ms;
      lit_pending_ = true;
      scene_stale_ = true;
      // The cloud replaces the ink: the footprint is cleared as the lit scene is drawn.
      overlay_.beginFootprint(session_->footprintWidth(), session_->footprintHeight());
    }
    cursor_.screen_px =
        glm::vec2(float(outcome.mapped.preview_x_px), float(outcome.mapped.preview_y_px));
    cursor_.visible = outcome.mapped.in_proximity;
  }
}

void PaintLoop::drawPaintingView(PaintFrameInfo* info) {
  const int w = display_.width(), h = display_.height();
  double sync_ms = 0.0, render_ms = 0.0;
  const auto render_start = std::chrono::steady_clock::now();
  const bool refine = refine_pending_ && !scene_stale_;
  if (scene_stale_ || refine) {
    renderer_.sync(shownVolume(), light_);  // the dirty box only: upload, occupancy, light (§4)
    const auto synced = std::chrono::steady_clock::now();
    sync_ms = std::chrono::duration<double, std::milli>(synced - render_start).count();
    // Right after a lift the cloud is shown first at the moving resolution (a quarter of the
    // rays at 0.5), then refined to full resolution on the next frame.
    RenderOptions options;
    options.collect_stats = show_stats_;
    options.scale =
        lit_pending_ ? std::clamp(options_.moving_scale, options_.min_moving_scale, 1.0f) : 1.0f;
    renderer_.render(session_->camera(), w, h, scene_.fbo(), options);
    if (lit_pending_) {
      glFinish();
      render_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - synced)
              .count();
    }
    overlay_.invalidate();
    scene_stale_ = false;
    refine_pending_ = options.scale < 1.0f;
  }
  if (lit_pending_) {
    // The footprint was just cleared, so the frame is the scene alone: a blit instead of the
    // overlay's full-frame composite (tens of ms on llvmpipe). The overlay composites the whole
    // frame, cursor included, on the next frame, which re-renders at full resolution anyway.
    glBlitNamedFramebuffer(scene_.fbo(), display_.framebuffer(), 0, 0, w, h, 0, 0, w, h,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    overlay_.invalidate();
  } else {
    overlay_.draw(scene_.texture(), display_.framebuffer(), w, h, cursor_);
  }
  info->painting_view = true;
  info->in_stroke = session_->engine().inStroke();
  info->texels_uploaded = texels_this_frame_;
  texels_this_frame_ = 0;
  if (lit_pending_ || refine) glFinish();  // the frame is really drawn, not only queued
  const double since_lift =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - lift_time_)
          .count();
  if (lit_pending_) {
    info->first_lit_after_lift = true;
    info->pen_up_to_lit_ms = since_lift;
    info->mapping_ms = lift_mapping_ms_;
    info->sync_ms = sync_ms;
    info->render_ms = render_ms;
    info->composite_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - render_start)
            .count() -
        sync_ms - render_ms;
    lit_pending_ = false;
  } else if (refine) {
    info->refined_after_lift = true;
    info->pen_up_to_refined_ms = since_lift;
  }
}

PaintLoop::PaintLoop(Display& display, VolumeRenderer& renderer, const Volume& volume,
                     const Light& light, const PaintLoopOptions& options)
    : display_(display),
      renderer_(renderer),
      volume_(volume),
      light_(light),
      options_(options),
      orbiting_(options.orbit_degrees_per_second != 0.0f),
      show_stats_(options.show_stats_overlay),
      show_circles_(options.show_circles_overlay) {}

void PaintLoop::cycleBrush() {
  if (!session_) {
    std::fprintf(stderr, "cloudbrush: B: no pen session, the brush is not used\n");
    return;
  }
  const BrushKind order[3] = {BrushKind::k2D, BrushKind::k3D, BrushKind::kSkeleton};
  int next = 0;
  for (int i = 0; i < 3; ++i)
    if (order[i] == session_->selectedBrush()) next = (i + 1) % 3;
  std::string error;
  const std::string text = std::string("brush=") + brushKindName(order[next]);
  if (!session_->applyUi(text, monotonicNowNs(), &error))
    std::fprintf(stderr, "cloudbrush: B: %s\n", error.c_str());
  else
    std::fprintf(stderr, "cloudbrush: %s (from the next stroke)\n", text.c_str());
}

void PaintLoop::cycleMapping() {
  if (!session_) {
    std::fprintf(stderr, "cloudbrush: M: no pen session, no mapping\n");
    return;
  }
  const MappingMethod next = session_->mappingMethod() == MappingMethod::kHybrid
                                 ? MappingMethod::kRayMarching
                                 : MappingMethod::kHybrid;
  std::string error;
  const std::string text = std::string("method=") + toString(next);
  if (!session_->applyUi(text, monotonicNowNs(), &error))
    std::fprintf(stderr, "cloudbrush: M: %s\n", error.c_str());
  else
    std::fprintf(stderr, "cloudbrush: %s (from the next stroke)\n", text.c_str());
}

bool PaintLoop::drawHud(std::string* error) {
  const bool in_range = pen_ && !orbiting_ && cursor_.visible;
  const bool circles = show_circles_ && session_ && !session_->lastCircles().empty();
  if (!show_stats_ && !circles && !in_range) return true;
  if (!hud_.init(error)) return false;
  const int w = display_.width(), h = display_.height();
  std::vector<HudItem> items;
  if (in_range) {
    const Volume& volume = shownVolume();
    appendCanvasOutline(canvasRegionOutline(session_->camera(), session_->canvas(),
                                            volume.worldMin(), volume.worldMax(), w, h),
                        &items);
  }
  if (circles)
    appendCircleRings(session_->lastCircles(), session_->footprintWidth(),
                      session_->footprintHeight(), w, h, &items);
  if (show_stats_) appendStatsPanel(renderer_.lastStats(), w, h, &items);
  hud_.draw(display_.framebuffer(), w, h, items);
  return true;
}

std::string PaintLoop::handleEvents() {
  std::vector<DisplayEvent> events;
  if (!initial_keys_pressed_) {
    initial_keys_pressed_ = true;
    for (DisplayEvent::Key key : options_.initial_keys) {
      DisplayEvent event;
      event.kind = DisplayEvent::Kind::KeyDown;
      event.key = key;
      events.push_back(event);
    }
  }
  for (const DisplayEvent& event : display_.pollEvents()) events.push_back(event);
  for (const DisplayEvent& event : events) {
    if (event.kind == DisplayEvent::Kind::Quit) return "window closed";
    if (event.isQuitRequest()) return event.key == DisplayEvent::Key::Q ? "q" : "Esc";
    if (event.kind == DisplayEvent::Kind::KeyDown && event.key == DisplayEvent::Key::Space) {
      orbiting_ = !orbiting_;
      refined_ = false;
      scene_stale_ = true;
    }
    if (event.kind == DisplayEvent::Kind::KeyDown) {
      switch (event.key) {
        case DisplayEvent::Key::S:
          show_stats_ = !show_stats_;
          refined_ = false;     // draw a still frame again, collecting statistics
          scene_stale_ = true;  // the painting view's cached scene too
          break;
        case DisplayEvent::Key::C:
          show_circles_ = !show_circles_;
          refined_ = false;
          break;
        case DisplayEvent::Key::B:
          cycleBrush();
          break;
        case DisplayEvent::Key::M:
          cycleMapping();
          break;
        default:
          break;
      }
    }
    if (event.kind == DisplayEvent::Kind::Resize) {
      refined_ = false;
      scene_stale_ = true;
    }
  }
  return "";
}

bool PaintLoop::run(const std::atomic<bool>* stop, PaintLoopSummary* summary, std::string* error) {
  *summary = PaintLoopSummary{};
  const auto start = std::chrono::steady_clock::now();
  auto last_present = start;
  std::vector<double> moving_frame_ms, painting_frame_ms;
  float scale = std::clamp(options_.moving_scale, options_.min_moving_scale, 1.0f);
  RenderOptions render_options;
  while (true) {
    std::string quit = handleEvents();
    if (quit.empty() && stop && stop->load()) quit = "signal";
    if (quit.empty() && options_.max_frames > 0 && summary->frames >= options_.max_frames)
      quit = "frame limit";
    if (!quit.empty()) {
      summary->quit_reason = quit;
      break;
    }
    if (pen_ && last_connection_ == int(PenConnection::kFinished) && !lit_pending_ &&
        !session_->engine().inStroke()) {
      summary->quit_reason = "replay finished";
      break;
    }
    if (pen_) handlePen(summary);
    if (pen_ && !orbiting_) {
      if (!paintingSetUp(error)) return false;
      PaintFrameInfo info;
      info.frame = summary->frames;
      drawPaintingView(&info);
      if (info.first_lit_after_lift) {
        summary->pen_up_to_lit_ms.push_back(info.pen_up_to_lit_ms);
        summary->mapping_ms.push_back(info.mapping_ms);
        summary->sync_ms.push_back(info.sync_ms);
        summary->render_ms.push_back(info.render_ms);
        if (options_.print_stats)
          std::printf(
              "stroke %ld: pen-up -> lit frame %.1f ms (mapping %.1f, sync %.1f, render "
              "%.1f, composite %.1f)\n",
              summary->strokes_mapped - 1, info.pen_up_to_lit_ms, info.mapping_ms, info.sync_ms,
              info.render_ms, info.composite_ms);
      }
      if (info.refined_after_lift) {
        summary->pen_up_to_refined_ms.push_back(info.pen_up_to_refined_ms);
        if (options_.print_stats)
          std::printf("stroke %ld: pen-up -> full-resolution lit frame %.1f ms\n",
                      summary->strokes_mapped - 1, info.pen_up_to_refined_ms);
      }
      if (!drawHud(error)) return false;
      if (options_.on_frame) options_.on_frame(info);
      if (!display_.present(error)) return false;
      const auto presented = std::chrono::steady_clock::now();
      // Frames while a stroke is drawn, except the lift frames (mapping + re-render).
      if (info.in_stroke && !info.first_lit_after_lift && !info.refined_after_lift)
        painting_frame_ms.push_back(
            std::chrono::duration<double, std::milli>(presented - last_present).count());
      last_present = presented;
      ++summary->frames;
      continue;
    }
    renderer_.sync(shownVolume(), light_);  // uploads only what changed (nothing, until painting)
    const bool moving = orbiting_;
    if (!moving && refined_) {
      // Still and already sharp: nothing to draw until something changes.
      std::this_thread::sleep_for(std::chrono::milliseconds(15));
      continue;
    }
    const auto now = std::chrono::steady_clock::now();
    if (moving)
      orbit_degrees_ += options_.orbit_degrees_per_second *
                        float(std::chrono::duration<double>(now - last_present).count());
    const Camera camera = Camera::reference().orbited(orbit_degrees_);
    // Quantised to 1/20 so the renderer's reduced-size target is not reallocated every frame.
    render_options.scale =
        moving ? std::max(options_.min_moving_scale, std::round(scale * 20.0f) / 20.0f) : 1.0f;
    render_options.collect_stats = (!moving && options_.print_stats) || show_stats_;
    glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
    renderer_.render(camera, display_.width(), display_.height(), display_.framebuffer(),
                     render_options);
    if (!drawHud(error)) return false;
    if (options_.on_frame) {
      PaintFrameInfo info;
      info.frame = summary->frames;
      options_.on_frame(info);
    }
    if (!display_.present(error)) return false;
    const auto presented = std::chrono::steady_clock::now();
    const double frame_ms =
        std::chrono::duration<double, std::milli>(presented - last_present).count();
    last_present = presented;
    ++summary->frames;
    if (moving && summary->frames > 1) {
      moving_frame_ms.push_back(frame_ms);
      // Keep the orbit fluid: shrink the resolution when a frame is over budget, grow it back
      // when there is room (≥ 20 fps is the target, issue 2).
      if (frame_ms > options_.target_frame_ms)
        scale = std::max(options_.min_moving_scale, scale * 0.9f);
      else if (frame_ms < 0.7 * options_.target_frame_ms)
        scale = std::min(1.0f, scale * 1.05f);
    }
    if (!moving) {
      refined_ = true;
      ++summary->refined_frames;
      if (options_.print_stats) std::printf("%s\n", renderer_.lastStats().summary().c_str());
    }
  }
  summary->seconds = secondsSince(start);
  summary->final_moving_scale = scale;
  summary->median_painting_frame_ms = medianOf(painting_frame_ms);
  summary->painting_frames = long(painting_frame_ms.size());
  if (!moving_frame_ms.empty()) {
    std::nth_element(moving_frame_ms.begin(),
                     moving_frame_ms.begin() + long(moving_frame_ms.size() / 2),
                     moving_frame_ms.end());
    summary->median_frame_ms = moving_frame_ms[moving_frame_ms.size() / 2];
  }
  std::vector<double> present_ms;
  const FrameTimingRing& timings = display_.frameTimings();
  for (size_t i = 0; i < timings.size(); ++i)
    present_ms.push_back(double(timings.at(i).shown_ns - timings.at(i).submit_ns) / 1e6);
  if (!present_ms.empty()) {
    std::nth_element(present_ms.begin(), present_ms.begin() + long(present_ms.size() / 2),
                     present_ms.end());
    summary->median_present_ms = present_ms[present_ms.size() / 2];
  }
  return true;
}

}  // namespace cb
