// The painter's morph and wind: the commands F, W, D, A, X and the per-frame advance.
// The animation plays on a copy (animation_preview.h) that the screen shows instead of the
// session's cloud; apply commits it through the session, leave drops it.
#include <algorithm>
#include <filesystem>

#include "app/shell/painter/animation_preview.h"
#include "app/shell/painter/paint_screen.h"

namespace cb {
namespace {

// The morph target when none was named: the newest saved cloud, else the bundled cumulus.
std::string defaultMorphTarget(const std::string& save_dir) {
  std::filesystem::path newest;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(save_dir, ec))
    if (entry.path().extension() == ".vol" &&
        (newest.empty() || entry.last_write_time() > std::filesystem::last_write_time(newest, ec)))
      newest = entry.path();
  return newest.empty() ? "bundled:1" : newest.string();
}

}  // namespace

bool PaintScreen::animationPlaying() const {
  return animation_ && animation_->playing();
}

void PaintScreen::onAnimationCommand(Command command, int64_t t_ns) {
  if (!session_) return say("morph and wind: no pen session, no cloud of yours to animate");
  if (!animation_) animation_ = std::make_unique<AnimationPreview>();
  std::string error;
  switch (command) {
    case Command::kMorph: {
      const std::string target =
          options_.morph_target.empty() ? defaultMorphTarget(saveDir()) : options_.morph_target;
      if (!animation_->startMorph(*session_, target, options_.morph_seconds, &error))
        return say(error);
      say("morphing into " + target + " over " + std::to_string(int(options_.morph_seconds)) +
          " s: A applies, X leaves");
      break;
    }
    case Command::kWind:
      if (!animation_->toggleWind(*session_, &error)) return say(error);
      say(animation_->status());
      break;
    case Command::kWindDirection:
      animation_->nextWindDirection();
      say(std::string("wind towards the ") + animation_->windDirectionName());
      break;
    case Command::kApplyAnimation: {
      const std::string what =
          animation_->active() ? formatUiChange(animation_->change()).text : "";
      if (!animation_->apply(session_, t_ns, &error)) return say(error);
      say("applied " + what);
      break;
    }
    case Command::kLeaveAnimation:
      if (!animation_->active()) return say("leave: no morph or wind is shown");
      animation_->leave();
      say("left the animation: the cloud is as it was");
      break;
    default:
      return;
  }
  refined_ = false;
  drawn_.reset();
}

void PaintScreen::advanceAnimation(const FrameContext& frame) {
  if (!animation_ || !animation_->active() || !session_) return;
  if (animation_->stale(*session_)) {
    animation_->leave();
    say("the cloud changed: left the morph / wind without applying");
    return;
  }
  // A morph's t moves with the clock (a long frame counts at most 0.25 s); the wind takes one
  // step per frame. The frames are drawn at the moving scale, refined when it stops.
  animation_->advanceTo(frame.now_ns);
}

}  // namespace cb
