#include "app/shell/painter/animation_preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/session/session_replay.h"
#include "app/volume/sky_extent.h"

namespace cb {
namespace {

constexpr const char* kDirectionNames[8] = {"east", "north-east", "north", "north-west",
                                            "west", "south-west", "south", "south-east"};

glm::vec2 directionXZ(int direction) {
  const float a = float(direction) * 0.25f * 3.14159265f;
  return {std::cos(a), -std::sin(a)};  // north is −z
}

// The display copy of the sky and the window's part of it (copied out: the frames are made on it).
struct Display {
  std::unique_ptr<Volume> shown, frame;
  glm::ivec3 at{0};
};

Display makeDisplay(const Volume& cloud, const ToolWindow& window, bool half) {
  Display d;
  d.shown = std::make_unique<Volume>(half ? halfResolution(cloud) : cloud);
  const VoxelBox box = half ? halfBox(window.box) : window.box;
  d.at = box.lo;
  d.frame = std::make_unique<Volume>(
      window.whole ? *d.shown : cropToWindow(*d.shown, box, window.world_min, window.world_max));
  return d;
}

}  // namespace

bool AnimationPreview::useHalf(const Volume& cloud, const ToolWindow& window) const {
  const std::optional<SkyExtent> sky = skyExtentOf(cloud);
  const int home = sky ? sky->grid : cloud.dims().x;
  // The window's half copy is the sky's half copy there only when it starts on even voxels.
  const bool even =
      window.box.lo.x % 2 == 0 && window.box.lo.y % 2 == 0 && window.box.lo.z % 2 == 0;
  return half_.value_or(home >= 128) && even;
}

void AnimationPreview::paste(const VoxelBox& region) {
  pasteVolume(*frame_, region, display_at_, shown_.get());
}

bool AnimationPreview::startMorph(const PaintSession& session, const std::string& target_source,
                                  double seconds, std::string* error) {
  const Volume& cloud = session.volume();
  try {
    const Volume target = loadMorphTarget(target_source, cloud);
    // One window for both clouds (their content's union), cropped out of each.
    const ToolWindow window = toolWindow(cloud, target);
    std::optional<Volume> source_crop, target_crop;
    if (!window.whole) {
      source_crop = cropToWindow(cloud, window);
      target_crop = cropToWindow(target, window);
    }
    const Volume& source_w = source_crop ? *source_crop : cloud;
    const Volume& target_w = target_crop ? *target_crop : target;
    // One plan from the full-resolution windows: the display copy moves along the same paths as
    // the frame apply commits (and replay recomputes).
    auto plan = std::make_shared<const MorphPlan>(source_w, target_w);
    const bool half = useHalf(cloud, window);
    Display display = makeDisplay(cloud, window, half);
    std::unique_ptr<CloudMorph> carried, full;
    if (half) {
      carried = std::make_unique<CloudMorph>(plan, *display.frame, halfResolution(target_w));
      // The full-resolution windows carried now, so apply only frames them.
      full = std::make_unique<CloudMorph>(plan, source_w, target_w);
    } else {
      carried = std::make_unique<CloudMorph>(plan, source_w, target_w);
    }
    const uint64_t checksum = volumeChecksum(target);
    leave();
    window_ = window;
    shown_ = std::move(display.shown);
    frame_ = std::move(display.frame);
    display_at_ = display.at;
    morph_ = std::move(carried);
    morph_full_ = std::move(full);
    target_checksum_ = checksum;
    target_ = target_source;
  } catch (const std::exception& e) {
    *error = std::string("morph: ") + e.what() + "; nothing started";
    return false;
  }
  kind_ = Kind::kMorph;
  playing_ = true;
  seconds_ = std::max(0.1, seconds);
  t_ = 0.0f;
  // The frame at t = 0 (the source carried along no distance), so what is shown is always a
  // frame of the record, from the first moment.
  written_ = morph_->frameInto(0.0f, frame_.get(), frame_->bounds());
  paste(frame_->bounds());
  base_dims_ = cloud.dims();
  base_instance_ = cloud.instanceId();
  base_generation_ = cloud.generation();
  return true;
}

bool AnimationPreview::toggleWind(const PaintSession& session, std::string* error) {
  if (kind_ == Kind::kWind) {
    playing_ = !playing_;
    last_advance_ns_ = -1;
    return true;
  }
  const Volume& cloud = session.volume();
  if (!cloud.hasDensity())
    return *error = "wind: the cloud is empty - paint or open one first", false;
  const ToolWindow window = toolWindow(cloud);
  Display display = makeDisplay(cloud, window, useHalf(cloud, window));
  leave();
  kind_ = Kind::kWind;
  playing_ = true;
  window_ = window;
  shown_ = std::move(display.shown);
  frame_ = std::move(display.frame);
  display_at_ = display.at;
  start_ = std::make_unique<Volume>(*frame_);
  written_ = frame_->bounds();
  spare_frame_ = std::make_unique<Volume>(*frame_);
  spare_written_ = frame_->bounds();
  wind_ = std::make_unique<WindAnimation>(window, WindRun{}.speed, WindRun{}.gust);
  const glm::vec2 d = directionXZ(direction_);
  wind_->setDirection(d.x, d.y);
  base_dims_ = cloud.dims();
  base_instance_ = cloud.instanceId();
  base_generation_ = cloud.generation();
  return true;
}

void AnimationPreview::nextWindDirection() {
  direction_ = (direction_ + 1) % 8;
  if (wind_ && kind_ == Kind::kWind) {
    dropWindAhead();  // stepped in the direction before
    const glm::vec2 d = directionXZ(direction_);
    wind_->setDirection(d.x, d.y);
  }
}

const char* AnimationPreview::windDirectionName() const {
  return kDirectionNames[direction_];
}

bool AnimationPreview::advance(double seconds) {
  if (!playing()) return false;
  const VoxelBox before = written_;
  if (kind_ == Kind::kMorph) {
    t_ = std::min(1.0f, t_ + float(seconds / seconds_));
    written_ = morph_->frameInto(t_, frame_.get(), written_);
    if (t_ >= 1.0f) playing_ = false;  // holds the target until applied or left
  } else {
    WindStep next = wind_ahead_.valid() ? wind_ahead_.get()
                                        : stepWind(copyOf(*wind_, std::move(spare_wind_)), *start_,
                                                   std::move(spare_frame_), spare_written_);
    spare_frame_ = std::move(frame_);
    spare_written_ = written_;
    spare_wind_ = std::move(wind_);
    wind_ = std::move(next.wind);
    frame_ = std::move(next.frame);
    written_ = next.written;
    startWindAhead();
  }
  // What was cleared and what was written: nothing else of the window changed.
  paste(before.unite(written_));
  return true;
}

std::unique_ptr<WindAnimation> AnimationPreview::copyOf(const WindAnimation& wind,
                                                        std::unique_ptr<WindAnimation> storage) {
  if (!storage) return std::make_unique<WindAnimation>(wind);
  *storage = wind;
  return storage;
}

AnimationPreview::WindStep AnimationPreview::stepWind(std::unique_ptr<WindAnimation> wind,
                                                      const Volume& start,
                                                      std::unique_ptr<Volume> frame,
                                                      const VoxelBox& previous) {
  wind->step();
  const VoxelBox written = wind->show(start, frame.get(), previous);
  return {std::move(wind), std::move(frame), written};
}

void AnimationPreview::startWindAhead() {
  // The thread copies the wind shown into the wind before it (its storage reused) and steps the
  // copy; meanwhile this object only reads the wind shown (fullFrame waits for the thread).
  wind_ahead_ =
      std::async(std::launch::async, [ahead = std::move(spare_wind_), shown = wind_.get(),
                                      start = start_.get(), frame = std::move(spare_frame_),
                                      previous = spare_written_]() mutable {
        return stepWind(copyOf(*shown, std::move(ahead)), *start, std::move(frame), previous);
      });
}

void AnimationPreview::dropWindAhead() {
  if (!wind_ahead_.valid()) return;
  try {
    WindStep dropped = wind_ahead_.get();
    spare_frame_ = std::move(dropped.frame);
    spare_written_ = dropped.written;
    spare_wind_ = std::move(dropped.wind);
  } catch (const std::exception&) {
    // The step failed: its frame went with it; the spare starts again from the frame shown.
    spare_frame_ = std::make_unique<Volume>(*frame_);
    spare_written_ = written_;
  }
}

bool AnimationPreview::advanceTo(int64_t now_ns) {
  const double seconds =
      last_advance_ns_ < 0 ? 0.0 : std::clamp(double(now_ns - last_advance_ns_) / 1e9, 0.0, 0.25);
  last_advance_ns_ = now_ns;
  return advance(seconds);
}

UiChange AnimationPreview::change() const {
  if (kind_ == Kind::kMorph) return ui::ApplyMorph{target_, target_checksum_, t_};
  return ui::ApplyWind{wind_ ? wind_->run() : WindRun{}};
}

WindowFrame AnimationPreview::fullFrame(const PaintSession& session) const {
  if (!atHalfResolution()) return {*frame_, window_.box.lo};
  if (kind_ == Kind::kMorph) return {morph_full_->frame(t_), window_.box.lo};
  // The wind's steps are done: its flow map carries the full-resolution window in one pass
  // (once the next frame's thread has read the wind: the pass keeps a copy of its start in it).
  if (wind_ahead_.valid()) wind_ahead_.wait();
  std::optional<Volume> cropped;
  if (!window_.whole) cropped = cropToWindow(session.volume(), window_);
  const Volume& start = cropped ? *cropped : session.volume();
  WindowFrame blown{start, window_.box.lo};
  wind_->show(start, &blown.volume, blown.volume.bounds());
  return blown;
}

bool AnimationPreview::apply(PaintSession* session, int64_t t_ns, std::string* error) {
  if (!active()) return *error = "apply: no morph or wind is shown", false;
  dropWindAhead();
  if (stale(*session)) {
    leave();
    return *error = "apply: the cloud changed since the animation started; left it", false;
  }
  try {
    if (!session->commitAnimation(change(), fullFrame(*session), t_ns, error)) return false;
  } catch (const std::exception& e) {
    return *error = std::string("apply: ") + e.what() + "; the cloud is unchanged", false;
  }
  leave();
  return true;
}

void AnimationPreview::leave() {
  dropWindAhead();
  spare_frame_.reset();
  spare_wind_.reset();
  kind_ = Kind::kNone;
  last_advance_ns_ = -1;
  playing_ = false;
  shown_.reset();
  frame_.reset();
  start_.reset();
  morph_.reset();
  morph_full_.reset();
  wind_.reset();
  t_ = 0.0f;
}

bool AnimationPreview::stale(const PaintSession& session) const {
  return active() && (session.volume().instanceId() != base_instance_ ||
                      session.volume().generation() != base_generation_);
}

std::string AnimationPreview::status() const {
  char text[200];
  if (kind_ == Kind::kMorph) {
    const std::string name = target_.substr(target_.find_last_of('/') + 1);
    std::snprintf(text, sizeof text, "Morphing into %s: %.0f%%%s - A applies, X leaves",
                  name.c_str(), 100.0 * double(t_), playing_ ? "" : " (done)");
    return text;
  }
  if (kind_ == Kind::kWind) {
    std::snprintf(text, sizeof text,
                  "Wind towards the %s, %d steps%s - W %s, D turns, A applies, X leaves",
                  windDirectionName(), windSteps(), playing_ ? "" : " (stopped)",
                  playing_ ? "stops" : "blows again");
    return text;
  }
  return "";
}

}  // namespace cb
