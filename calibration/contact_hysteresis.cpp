#include "calibration/contact_hysteresis.h"

namespace cb {

bool ContactHysteresis::update(float pressure) {
  if (!(pressure == pressure)) return down_;  // NaN: keep the state
  if (down_) {
    if (pressure < thresholds_.up) down_ = false;
  } else if (pressure >= thresholds_.down) {
    down_ = true;
  }
  return down_;
}

}  // namespace cb
