#include "app/shell/animation_preview.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/session/session_replay.h"

namespace cb {
namespace {

constexpr const char* kDirectionNames[8] = {"east", "north-east", "north", "north-west",
                                            "west", "south-west", "south", "south-east"};

glm::vec2 directionXZ(int direction) {
  const float a = float(direction) * 0.25f * 3.14159265f;
  return {std::cos(a), -std::sin(a)};  // north is −z
}

}  // namespace

bool AnimationPreview::startMorph(const PaintSession& session, const std::string& target_source,
                                  double seconds, std::string* error) {
  const bool half = useHalf(session.volume());
  try {
    auto target = std::make_unique<Volume>(loadMorphTarget(target_source, session.volume()));
    // One plan from the full-resolution clouds: the display copy moves along the same paths as
    // the frame apply commits (and replay recomputes).
    auto plan = std::make_shared<const MorphPlan>(session.volume(), *target);
    std::unique_ptr<CloudMorph> carried, full;
    std::unique_ptr<Volume> shown;
    if (half) {
      shown = std::make_unique<Volume>(halfResolution(session.volume()));
      carried = std::make_unique<CloudMorph>(plan, *shown, halfResolution(*target));
      // The full-resolution clouds carried now, so apply only frames them.
      full = std::make_unique<CloudMorph>(plan, session.volume(), *target);
    } else {
      shown = std::make_unique<Volume>(session.volume());
      carried = std::make_unique<CloudMorph>(plan, session.volume(), *target);
    }
    leave();
    morph_ = std::move(carried);
    shown_ = std::move(shown);
    target_checksum_ = volumeChecksum(*target);
    morph_full_ = std::move(full);
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
  written_ = morph_->frameInto(0.0f, shown_.get(), shown_->bounds());
  base_dims_ = session.volume().dims();
  base_instance_ = session.volume().instanceId();
  base_generation_ = session.volume().generation();
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
  leave();
  kind_ = Kind::kWind;
  playing_ = true;
  start_ = std::make_unique<Volume>(useHalf(session.volume()) ? halfResolution(session.volume())
                                                              : session.volume());
  shown_ = std::make_unique<Volume>(*start_);
  written_ = shown_->bounds();
  wind_ = std::make_unique<WindAnimation>(*shown_, WindRun{}.speed, WindRun{}.gust);
  const glm::vec2 d = directionXZ(direction_);
  wind_->setDirection(d.x, d.y);
  base_dims_ = session.volume().dims();
  base_instance_ = session.volume().instanceId();
  base_generation_ = session.volume().generation();
  return true;
}

void AnimationPreview::nextWindDirection() {
  direction_ = (direction_ + 1) % 8;
  if (wind_ && kind_ == Kind::kWind) {
    const glm::vec2 d = directionXZ(direction_);
    wind_->setDirection(d.x, d.y);
  }
}

const char* AnimationPreview::windDirectionName() const {
  return kDirectionNames[direction_];
}

bool AnimationPreview::advance(double seconds) {
  if (!playing()) return false;
  if (kind_ == Kind::kMorph) {
    t_ = std::min(1.0f, t_ + float(seconds / seconds_));
    written_ = morph_->frameInto(t_, shown_.get(), written_);
    if (t_ >= 1.0f) playing_ = false;  // holds the target until applied or left
    return true;
  }
  wind_->step();
  written_ = wind_->show(*start_, shown_.get(), written_);
  return true;
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

Volume AnimationPreview::fullFrame(const PaintSession& session) const {
  if (!atHalfResolution()) return *shown_;
  if (kind_ == Kind::kMorph) return morph_full_->frame(t_);
  // The wind's steps are done: its flow map carries the full-resolution cloud in one pass.
  Volume blown = session.volume();
  wind_->show(session.volume(), &blown, blown.bounds());
  return blown;
}

bool AnimationPreview::apply(PaintSession* session, int64_t t_ns, std::string* error) {
  if (!active()) return *error = "apply: no morph or wind is shown", false;
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
  kind_ = Kind::kNone;
  last_advance_ns_ = -1;
  playing_ = false;
  shown_.reset();
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
