#include "app/shell/calibrate/calibrate_wait_screen.h"

#include "drivers/core/pen_source.h"

namespace cb {

void CalibrateWaitScreen::check() {
  if (done_ || !context_.pen) return;
  const PenConnection connection = context_.pen->connection();
  if (connection == PenConnection::kConnected) {
    done_ = true;
    on_done_(true, "");
  } else if (connection == PenConnection::kPermissionDenied ||
             connection == PenConnection::kFinished) {
    done_ = true;
    on_done_(false, "no pen: " + context_.pen->statusMessage());
  }
}

std::string CalibrateWaitScreen::update(const FrameContext& frame) {
  (void)frame;
  check();
  return "";
}

bool CalibrateWaitScreen::needsFrame() const {
  // Redrawn when what it says changes; otherwise the loop sleeps between looks at the pen.
  return !drawn_ || (context_.pen && context_.pen->statusMessage() != drawn_status_);
}

bool CalibrateWaitScreen::draw(FrameContext& frame, std::string* error) {
  const std::string status = context_.pen ? context_.pen->statusMessage() : "no pen source";
  CalibrateView& v = context_.view;
  v.begin(frame.display.framebuffer(), frame.width, frame.height, {0.25f, 0.05f, 0.05f});
  v.say({"Waiting for the pen", "Connect the tablet and bring the pen near it.", status,
         "Calibration starts by itself when the pen is there.", context_.esc_hint},
        0.35f);
  drawn_ = true;
  drawn_status_ = status;
  return v.finish(error);
}

}  // namespace cb
