// Pen contact from pressure with hysteresis: down when the (offset-corrected) pressure reaches
// the upper threshold, up only when it falls below the lower one, so a pen resting with a
// noisy light pressure never chatters between stroke and no stroke. Defaults are libinput's
// tablet pressure thresholds (5 % down, 1 % up, of the range above the nib offset); the
// device's own BTN_TOUCH is not used when the pen reports pressure.
#pragma once

namespace cb {

struct ContactThresholds {
  float down = 0.05f;
  float up = 0.01f;
};

class ContactHysteresis {
 public:
  ContactHysteresis() = default;
  explicit ContactHysteresis(const ContactThresholds& t) : thresholds_(t) {}
  void setThresholds(const ContactThresholds& t) { thresholds_ = t; }
  const ContactThresholds& thresholds() const { return thresholds_; }

  // Feeds one pressure (0..1) and returns the contact state after it.
  bool update(float pressure);
  // Proximity out: the pen is up.
  void reset() { down_ = false; }
  bool down() const { return down_; }

 private:
  ContactThresholds thresholds_;
  bool down_ = false;
};

}  // namespace cb
