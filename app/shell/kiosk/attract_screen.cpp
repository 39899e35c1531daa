#include "app/shell/kiosk/attract_screen.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/kiosk/gallery_store.h"
#include "app/render/gl/gl.h"
#include "app/render/render_style.h"
#include "app/session/session_replay.h"

namespace cb {

AttractScreen::AttractScreen(VolumeRenderer& renderer, const Clock& clock,
                             std::vector<JournalRecord> journal, AttractOptions options,
                             UiOverlay* ui)
    : renderer_(renderer), clock_(clock), options_(std::move(options)), ui_(ui) {
  // The journal's own session settings (screen, format, auto-end), brush and mapping, so the
  // replay is the one `cloudbrush replay` gives whatever the local config; the grid may be the
  // kiosk's.
  RecordedSettings recorded = recordedSettings(journal, options_.brush, options_.mapping);
  settings_ = recorded.settings;
  options_.brush = recorded.brush;
  options_.mapping = recorded.mapping;
  for (const std::string& problem : recorded.problems)
    problems_.push_back("attract journal: " + problem);
  if (options_.grid > 0) settings_.grid = options_.grid;
  replay_ = std::make_unique<AttractReplay>(std::move(journal), settings_, options_.brush,
                                            options_.mapping, options_.light);
  start_scale_ = options_.render.scale;
  restart();
}

AttractScreen::~AttractScreen() = default;

void AttractScreen::restart() {
  started_ns_ = clock_.nowNs();
  last_update_ns_ = started_ns_;
  if (orbit_start_ns_ < 0) orbit_start_ns_ = started_ns_;
  finished_ns_ = replay_->recordCount() == 0 ? started_ns_ : -1;
  next_ = 0;
  shown_ = replay_->keyframeAt(0);
  morph_.reset();
  morphs_ = 0;
  session_.reset();
  morph_applied_ = false;
  camera_ = shown_.camera;
  // Each loop starts at the given scale, as the first did, and adapts from there (presented):
  // what the renderer holds follows the scale (its frame targets, llvmpipe's bins: 243 MB of
  // VmRSS at 0.2 against 273 MB at 1.0 in the kiosk soak), so a kiosk whose loop kept the scale
  // the machine's load last left it at held a different amount after each reset.
  options_.render.scale = start_scale_;
}

void AttractScreen::setTexts(std::string invitation, std::string hint, std::string notice) {
  options_.invitation = std::move(invitation);
  options_.hint = std::move(hint);
  options_.notice = std::move(notice);
}

std::string AttractScreen::update(const FrameContext& frame) {
  (void)frame;
  const int64_t now = clock_.nowNs();
  const std::vector<std::string> replay_problems = replay_->problems();
  for (; problems_seen_ < replay_problems.size(); ++problems_seen_) {
    problems_.push_back(replay_problems[problems_seen_]);
    std::fprintf(stderr, "cloudbrush kiosk: %s\n", problems_.back().c_str());
  }
  if (morph_ && morph_->playing()) {
    morph_->advanceTo(now);
    if (!morph_->playing()) finished_ns_ = now;  // the gallery cloud holds, then goes on
  } else if (finished_ns_ < 0) {
    // Every record due by now, at the journal's pace: record time since the first record,
    // against clock time since the start, times the speed; never past what the worker mapped.
    const size_t count = replay_->recordCount(), mapped = replay_->recordsReplayed();
    const auto due = [&](size_t i) {
      return double(replay_->recordTime(i)) / 1e9 <=
             double(now - started_ns_) / 1e9 * options_.speed;
    };
    const size_t before = next_;
    while (next_ < count && next_ < mapped && due(next_)) ++next_;
    // The worker is behind the clock: the replay holds where it is until it catches up.
    if (next_ < count && next_ == mapped && due(next_)) started_ns_ += now - last_update_ns_;
    if (next_ != before) shown_ = replay_->keyframeAt(next_);
    if (next_ == count) finished_ns_ = now;
  } else if (replay_->recordCount() > 0 && double(now - finished_ns_) / 1e9 >= options_.hold_s) {
    if (morph_ && morph_->active()) {
      // The gallery cloud shown becomes the session's (t = 1: the cloud itself).
      std::string error;
      if (!morph_->apply(session_.get(), now, &error)) problems_.push_back("attract: " + error);
      morph_applied_ = true;
      morph_.reset();
    }
    if (!startNextMorph()) {
      ++loops_;
      restart();
    }
  }
  last_update_ns_ = now;
  const float degrees =
      options_.orbit_degrees_per_second * float(double(now - orbit_start_ns_) / 1e9);
  camera_ = shown_.camera.orbited(degrees);
  return "";
}

const Volume& AttractScreen::shownVolume() const {
  return morphing() ? morph_->shown() : volume();
}

bool AttractScreen::startNextMorph() {
  if (options_.gallery_dir.empty() || morphs_ >= options_.gallery_morphs) return false;
  // Newest first: the entry below the last one shown, else (wrapping) the newest.
  const std::vector<GalleryEntry> entries = GalleryStore(options_.gallery_dir, 0, 0.0).entries();
  std::vector<const GalleryEntry*> order;
  for (auto it = entries.rbegin(); it != entries.rend(); ++it)
    if (last_gallery_ < 0 || it->number < last_gallery_) order.push_back(&*it);
  for (auto it = entries.rbegin(); it != entries.rend(); ++it)
    if (last_gallery_ >= 0 && it->number >= last_gallery_) order.push_back(&*it);
  if (!session_ && !order.empty()) {
    // The replayed cloud, in a session the morphs start from.
    session_ = std::make_unique<PaintSession>(settings_, options_.brush, options_.mapping);
    session_->setStartingLight(shown_.light);
    std::string error;
    if (!session_->replaceVolume(*shown_.volume, clock_.nowNs(), "attract replay", &error)) {
      problems_.push_back("attract: " + error);
      session_.reset();
      return false;
    }
  }
  for (const GalleryEntry* entry : order) {
    last_gallery_ = entry->number;
    auto morph = std::make_unique<AnimationPreview>();
    std::string error;
    const std::string cloud = entry->path + "/cloud.cbvol";
    if (!morph->startMorph(*session_, cloud, options_.morph_seconds, &error)) {
      if (problems_.size() < 20) problems_.push_back("attract: gallery " + cloud + ": " + error);
      continue;
    }
    morph_ = std::move(morph);
    morph_->advanceTo(clock_.nowNs());  // the morph's time starts now
    ++morphs_;
    return true;
  }
  return false;
}

void AttractScreen::presented(const FrameContext& frame, double frame_ms) {
  given_up_in_a_row_ = 0;
  if (frame.frame == 0) return;  // the first frame compiles shaders
  last_frame_ms_ = frame_ms;
  float& scale = options_.render.scale;
  if (frame_ms > 50.0)
    scale = std::max(0.2f, scale * 0.9f);
  else if (frame_ms < 35.0)
    scale = std::min(1.0f, scale * 1.05f);
}

int AttractScreen::slices() const {
  if (options_.slice_ms <= 0.0 || last_frame_ms_ <= options_.slice_ms) return 1;
  return std::clamp(int(std::ceil(last_frame_ms_ / options_.slice_ms)), 1,
                    std::max(1, options_.max_slices));
}

bool AttractScreen::drawnUnlessInputWaits(FrameContext& frame) {
  // A run of frames given up for input that never hands over (a tablet flapping) still shows
  // every kMaxGivenUpInARow + 1-th frame whole.
  constexpr int kMaxGivenUpInARow = 8;
  const bool may_give_up = frame.input_waiting && given_up_in_a_row_ < kMaxGivenUpInARow;
  const auto waiting = [&] { return may_give_up && frame.input_waiting(); };
  if (waiting()) return false;
  // What was sent is drawn while the pen is watched: a pen arriving meanwhile gives the frame up
  // without waiting for it (the GPU finishes it ahead of the next frame's commands).
  GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  bool done = false;
  while (!done && !waiting()) {
    const GLenum r = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 2'000'000);  // 2 ms
    done = r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED || r == GL_WAIT_FAILED;
  }
  glDeleteSync(fence);
  return done;
}

bool AttractScreen::giveUp(FrameContext& frame, int slices) {
  frame.abandoned = true;
  ++given_up_in_a_row_;
  ++frames_given_up_;
  std::fprintf(stderr,
               "cloudbrush kiosk: attract frame given up for the pen after %d of %d slices\n",
               slices_finished_, slices);
  return true;
}

bool AttractScreen::draw(FrameContext& frame, std::string* error) {
  (void)error;
  const int slices = this->slices();
  slices_finished_ = 0;
  slice_started_ns_ = MonotonicClock().nowNs();
  renderer_.sync(shownVolume(), shown_.light);
  RenderOptions render = options_.render;
  // Quantised to 1/20 so the renderer's reduced-size target is not reallocated every frame.
  render.scale = std::max(0.2f, std::round(render.scale * 20.0f) / 20.0f);
  render.style = parseRenderStyle(shown_.style).value_or(render.style);
  render.moving = render.scale < 1.0f;
  glBindFramebuffer(GL_FRAMEBUFFER, frame.display.framebuffer());
  if (slices == 1) {
    renderer_.render(camera_, frame.width, frame.height, frame.display.framebuffer(), render);
    slices_finished_ = 1;
  } else {
    if (!drawnUnlessInputWaits(frame)) return giveUp(frame, slices);  // the sync's uploads
    // Bands of rows, bottom up (the renderer's region: the rest of the target is left as it
    // is, and each band's pixels are those of the whole frame).
    for (int k = 0; k < slices; ++k) {
      const int y0 = frame.height * k / slices, y1 = frame.height * (k + 1) / slices;
      render.region = glm::ivec4(0, y0, frame.width, y1 - y0);
      slice_started_ns_ = MonotonicClock().nowNs();
      renderer_.render(camera_, frame.width, frame.height, frame.display.framebuffer(), render);
      if (!drawnUnlessInputWaits(frame)) return giveUp(frame, slices);
      ++slices_finished_;
    }
  }
  if (!ui_) return true;
  const float h = float(frame.height), w = float(frame.width);
  std::vector<UiLabel> labels;
  labels.push_back(
      {0.5f * w, 0.38f * h, options_.invitation, 0.075f * h, 0xffffffffu, true, 0x00000088u});
  labels.push_back({0.5f * w, 0.52f * h, options_.hint, std::max(16.0f, 0.04f * h), 0xffe9b0ffu,
                    true, 0x00000088u});
  if (!options_.notice.empty()) {
    const float size = std::max(14.0f, 0.026f * h);
    labels.push_back(
        {0.5f * w, h - 3.2f * size, options_.notice, size, 0xd8e4f0ffu, true, 0x000000aau});
  }
  glBindFramebuffer(GL_FRAMEBUFFER, frame.display.framebuffer());
  glViewport(0, 0, frame.width, frame.height);
  slice_started_ns_ = MonotonicClock().nowNs();
  ui_->drawLabels(frame.width, frame.height, labels);
  if (slices > 1 && !drawnUnlessInputWaits(frame)) return giveUp(frame, slices);
  return true;
}

}  // namespace cb
