// The N-point calibration, as data and pure steps, shared by the on-screen `cloudbrush
// calibrate` and its non-interactive paths (a tap file, a recorded calibration journal):
//
//   1. targetLayout(): where the targets are drawn (corners and centre, or a 3x3 grid), inset
//      from the screen edges;
//   2. TapCollector: turns the positions of each tap into one position in tablet mm (the
//      median of the samples in contact, robust to the slip at touch-down and lift; a tap that
//      drags more than a few mm is refused). It does not decide when the pen is down: the
//      shell's pen events (app/shell/pen_events.h, from the calibrated contact) tell it;
//   3. fitCalibration(): maps the taps through the profile's area mapping alone and fits the
//      correction (affine or homography) from there to the targets, with residuals in px; the
//      profile it returns names the device it was measured on.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "calibration/calibration_profile.h"
#include "drivers/core/pen_sample.h"

namespace cb {

// 5: four corners and the centre; 9: a 3x3 grid (corners, edge midpoints, centre). Targets are
// inset by `inset` of the screen size from each edge. Order: row by row from the top left,
// except that 5 goes corners clockwise from the top left, then the centre.
std::vector<glm::dvec2> targetLayout(int count, int screen_w, int screen_h, double inset = 0.1);

struct Tap {
  glm::dvec2 target_px{0.0};
  glm::dvec2 pen_mm{0.0};
};

class TapCollector {
 public:
  struct Params {
    size_t min_samples = 3;    // 15 ms at 200 Hz
    double max_drag_mm = 4.0;  // a tap, not a stroke
  };
  TapCollector() = default;
  explicit TapCollector(const Params& params) : params_(params) {}

  // The pen went down at `pen_mm` (raw tablet mm of the sample that put it down).
  void down(glm::dvec2 pen_mm);
  // A sample in contact after that.
  void move(glm::dvec2 pen_mm);
  // The pen lifted (or left proximity): the tap position, or nullopt with lastRejection().
  std::optional<glm::dvec2> up();
  // Why the last contact was not accepted as a tap (too short, dragged), empty otherwise.
  const std::string& lastRejection() const { return rejection_; }
  bool inContact() const { return in_contact_; }

 private:
  Params params_;
  bool in_contact_ = false;
  std::vector<glm::dvec2> points_;
  std::string rejection_;
};

struct CalibrationFit {
  bool ok = false;
  std::string error;
  CalibrationProfile profile;  // the input profile with the new correction and device
  PointFitResult fit;          // residuals in screen px
};

// `base` supplies the area mapping (and everything else kept as is). `taps` must hold at least
// 3 (affine) or 4 (homography) points.
CalibrationFit fitCalibration(const CalibrationProfile& base, const PenDeviceInfo& device,
                              uint64_t tool_serial, int screen_w, int screen_h,
                              const std::vector<Tap>& taps, PointFitKind kind);

// The fit as lines of text: the kind and point count, each target with its tap and residual,
// and the rms / max residual (what `cloudbrush calibrate` prints).
std::string describeFit(const CalibrationFit& fit, const std::vector<Tap>& taps);

// A tap file (the non-interactive input of `cloudbrush calibrate --points FILE`):
//   [screen]  width = 1920, height = 1080
//   [device]  usb_vendor = 0x056a, usb_product = 0x00b9, width_mm = 223.52, height_mm = 139.7
//   [[tap]]   target_px = [192.0, 108.0], pen_mm = [22.4, 14.0]      (one per tap)
struct TapFile {
  int screen_w = 0, screen_h = 0;
  PenDeviceInfo device;  // vendor, product, and a 100 units/mm range matching the size
  std::vector<Tap> taps;
};
// Errors name the file and line.
std::optional<TapFile> parseTapFile(std::string_view text, const std::string& name,
                                    std::string* error);

}  // namespace cb
