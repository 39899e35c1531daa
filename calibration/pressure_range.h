// The participant's pressure range: a quick two-step calibration (press lightly, press firmly)
// at the start of a session sets which part of the pen's range feeds the pressure curve, so a
// light-handed participant still reaches full ink and a heavy-handed one still has room.
// It belongs to the session (journalled with it), not to the device profile.
//
//   u = clamp((p' - lo) / (hi - lo), 0, 1)      p': offset-corrected pressure, u: curve input
//
// hi is the firm press (its 90th percentile: the press the participant can hold), lo is chosen
// so the light press (its median) lands at `light_target` on the curve's input:
//   lo = (light - light_target * hi) / (1 - light_target), at least 0.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cb {

struct PressureRange {
  float lo = 0.0f;
  float hi = 1.0f;
  float apply(float pressure) const;
};

struct PressureRangeFit {
  std::optional<PressureRange> range;
  std::string error;  // why no range could be set (too few samples, firm not firmer than light)
  float light = 0.0f, firm = 0.0f;  // the measured press levels
};

// `light` and `firm` are offset-corrected pressures of the samples in contact during each step.
PressureRangeFit fitPressureRange(std::vector<float> light, std::vector<float> firm,
                                  float light_target = 0.2f);

// The two-step press calibration as a state machine: feed pen samples; it waits for a light
// press held for `hold_samples` samples in contact and lifted, then a firm one, then fits.
// Whether the pen is in contact is decided by the caller (the calibrated contact, as the
// shell's pen events report it), never here.
class PressureRangeCollector {
 public:
  enum class Step { kLight, kFirm, kDone };
  explicit PressureRangeCollector(size_t hold_samples = 100, float light_target = 0.2f)
      : hold_samples_(hold_samples), light_target_(light_target) {}
  // One sample: `contact` the pen is down, `pressure` its offset-corrected pressure
  // (MappedSample::pressure_corrected).
  void feed(bool contact, float pressure);
  Step step() const { return step_; }
  // Samples held in contact during the current step (for a progress bar).
  size_t held() const { return current_.size(); }
  size_t holdSamples() const { return hold_samples_; }
  // Valid once step() is kDone.
  const PressureRangeFit& result() const { return result_; }
  void restart();

 private:
  size_t hold_samples_;
  float light_target_;
  Step step_ = Step::kLight;
  std::vector<float> current_, light_;
  PressureRangeFit result_;
};

// "[pressure_range]\nlo = ..\nhi = ..\n": the session record's text, and back. parse returns
// nullopt (and says why: "NAME:LINE: pressure_range.lo: what", NAME the file the text came
// from, "line LINE: ..." without one) for anything else.
std::string pressureRangeToToml(const PressureRange& range);
std::optional<PressureRange> pressureRangeFromToml(const std::string& text, std::string* error,
                                                   std::string_view name = {});

}  // namespace cb
