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
  try {
    const Volume target = loadMorphTarget(target_source, session.volume());
    auto plan = std::make_unique<CloudMorph>(session.volume(), target);
    leave();
    morph_ = std::move(plan);
    target_ = target_source;
    target_checksum_ = volumeChecksum(target);
  } catch (const std::exception& e) {
    *error = std::string("morph: ") + e.what() + "; nothing started";
    return false;
  }
  kind_ = Kind::kMorph;
  playing_ = true;
  seconds_ = std::max(0.1, seconds);
  t_ = 0.0f;
  shown_ = std::make_unique<Volume>(session.volume());
  // The frame at t = 0 (the source carried along no distance), so what is shown is always a
  // frame that the record recomputes, from the first moment.
  written_ = morph_->frameInto(0.0f, shown_.get(), shown_->bounds());
  base_instance_ = session.volume().instanceId();
  base_generation_ = session.volume().generation();
  return true;
}

void AnimationPreview::toggleWind(const PaintSession& session) {
  if (kind_ == Kind::kWind) {
    playing_ = !playing_;
    return;
  }
  leave();
  kind_ = Kind::kWind;
  playing_ = true;
  shown_ = std::make_unique<Volume>(session.volume());
  wind_ = std::make_unique<WindAnimation>(*shown_, WindRun{}.speed, WindRun{}.gust);
  const glm::vec2 d = directionXZ(direction_);
  wind_->setDirection(d.x, d.y);
  base_instance_ = session.volume().instanceId();
  base_generation_ = session.volume().generation();
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
  wind_->step(shown_.get());
  return true;
}

UiChange AnimationPreview::change() const {
  if (kind_ == Kind::kMorph) return ui::ApplyMorph{target_, target_checksum_, t_};
  return ui::ApplyWind{wind_ ? wind_->run() : WindRun{}};
}

bool AnimationPreview::apply(PaintSession* session, int64_t t_ns, std::string* error) {
  if (!active()) return *error = "apply: no morph or wind is shown", false;
  if (stale(*session)) {
    leave();
    return *error = "apply: the cloud changed since the animation started; left it", false;
  }
  if (!session->commitAnimation(change(), *shown_, t_ns, error)) return false;
  leave();
  return true;
}

void AnimationPreview::leave() {
  kind_ = Kind::kNone;
  playing_ = false;
  shown_.reset();
  morph_.reset();
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
    std::snprintf(text, sizeof text, "morph into %s %3.0f%%%s: A applies, X leaves",
                  target_.c_str(), 100.0 * double(t_), playing_ ? "" : " (done)");
    return text;
  }
  if (kind_ == Kind::kWind) {
    std::snprintf(text, sizeof text,
                  "wind towards the %s, %d steps%s: W %s, D turns, A applies, X leaves",
                  windDirectionName(), windSteps(), playing_ ? "" : " (stopped)",
                  playing_ ? "stops" : "blows again");
    return text;
  }
  return "";
}

}  // namespace cb
