// The painter's late ink (PaintLoopOptions::late_ink): while a stroke is drawn, the frame —
// the cached scene with the ink, the heads-up items, the UI — is made first, then the pen
// samples that came meanwhile are latched and only the pixels their ink and the cursor changed
// are drawn again, in the whole path's order (scene and ink, heads-up items, UI), so each pixel
// is what the whole path would draw from the same samples. A sample then waits for its own ink
// rather than for a whole frame.
#include <cstring>

#include "app/shell/painter/paint_screen.h"
#include "app/shell/ui_overlay.h"

namespace cb {
namespace {

bool sameItems(const std::vector<HudItem>& a, const std::vector<HudItem>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(HudItem)) == 0);
}

}  // namespace

bool PaintScreen::lateInkApplies(const FrameContext& frame, const PaintFrameInfo& info) const {
  // Samples the on-screen UI holds (menu open, pen over a target) are not ink: they wait for
  // the next frame, so the UI sees every press and release in its own frame.
  const bool ui_holds_pen = menu_open_ || pointer_over_ui_ || (session_ && session_->penCaptured());
  return options_.late_ink && frame.latch_pen && info.painting_view && inkLive() &&
         !info.first_lit_after_lift && !info.refined_after_lift && !ui_holds_pen && ui_ &&
         !ui_failed_;
}

bool PaintScreen::drawLateInk(FrameContext& frame, PaintFrameInfo* info, std::string* error) {
  // llvmpipe draws at the flush: finish the frame made so far, so a sample latched now waits
  // only for the few pixels of its ink.
  glFinish();
  frame.latch_pen();
  std::vector<HudItem> items = hudItems();
  if (!inkLive() || lit_pending_ || sceneStale() || !sameItems(items, hud_items_)) {
    // The samples changed more than the ink (a lift, the view, the heads-up items): the whole
    // frame again, from them.
    PaintFrameInfo again;
    again.frame = info->frame;
    if (!drawPass(frame, &again, error)) return false;
    again.texels_uploaded += info->texels_uploaded;
    *info = again;
    return true;
  }
  const int w = display_.width(), h = display_.height();
  const glm::ivec4 box =
      overlay_.drawChanges(scene_.texture(), display_.framebuffer(), w, h, cursor_);
  info->late_ink = true;
  info->texels_uploaded += texels_this_frame_;
  texels_this_frame_ = 0;
  if (box.z <= box.x || box.w <= box.y) return true;  // nothing came
  std::memcpy(info->late_box, &box.x, sizeof(info->late_box));
  if (!items.empty()) hud_.draw(display_.framebuffer(), w, h, items, &box);
  glBindFramebuffer(GL_FRAMEBUFFER, display_.framebuffer());
  glViewport(0, 0, w, h);
  ui_->redraw(box);
  return true;
}

}  // namespace cb
