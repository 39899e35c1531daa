// A calibration profile: everything that turns one device's raw pen samples into screen
// samples (area mapping, N-point correction, pressure, tilt, smoothing, prediction), stored as
// TOML. Shipped defaults live in config/calibration.toml (no [device]: they fit any pen); the
// kiosk's own profiles, written by `cloudbrush calibrate`, carry the USB id and, when known, the
// tool serial, and are never applied to another device.
//
// Parsing is strict about values (wrong type, out of range -> an error naming file and line,
// and no profile) and lenient about unknown keys (a warning each, so a profile written by a
// later version still loads).
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "calibration/area_mapping.h"
#include "calibration/contact_hysteresis.h"
#include "calibration/nib_offset.h"
#include "calibration/one_euro_filter.h"
#include "calibration/point_fit.h"
#include "calibration/pressure_curve.h"
#include "calibration/preview_predictor.h"
#include "calibration/tilt.h"
#include "drivers/core/pen_sample.h"

namespace cb {

// Which pen a profile belongs to. No vendor/product: any device (the shipped defaults).
// tool_serial 0: any tool of that device.
struct DeviceMatch {
  std::optional<uint16_t> usb_vendor, usb_product;
  uint64_t tool_serial = 0;
  std::string name;  // informational

  bool anyDevice() const { return !usb_vendor && !usb_product; }
  bool matches(const PenDeviceInfo& device, uint64_t tool_serial) const;
  std::string describe() const;  // "056a:00b9 serial 0x1234" or "any device"
};

struct PressureSettings {
  std::array<double, 4> curve{0, 0, 100, 100};  // PressCurve x1 y1 x2 y2
  ContactThresholds contact;
  NibOffsetParams nib;
  float light_target = 0.2f;  // where the light press lands in the participant calibration
};

struct SmoothingSettings {
  // Position in tablet millimetres (beta per mm/s), tilt in degrees (beta per deg/s).
  OneEuroParams position{1.0, 0.3, 2.0};  // tuned with `cloudbrush bench smoothing`
  OneEuroParams tilt{1.0, 0.01, 1.0};
};

struct CalibrationProfile {
  DeviceMatch device;
  AreaMappingConfig area;
  // N-point correction applied after the area mapping, in screen pixels.
  PointFitKind fit_kind = PointFitKind::kNone;
  glm::dmat3 correction{1.0};
  double fit_rms_px = 0.0, fit_max_px = 0.0;
  int fit_points = 0;
  PressureSettings pressure;
  TiltZero tilt_zero;
  SmoothingSettings smoothing;
  PredictionParams prediction;
};

struct ProfileParseResult {
  std::optional<CalibrationProfile> profile;  // nullopt when there was any error
  std::vector<std::string> errors;            // "file:line: what"
  std::vector<std::string> warnings;          // unknown keys
};

// `source_name` names the file in messages. Missing keys keep their defaults.
ProfileParseResult parseCalibrationProfile(std::string_view text, const std::string& source_name);
ProfileParseResult readCalibrationProfile(const std::string& path);

// TOML text that parses back to an equal profile (doubles printed to round-trip exactly).
std::string formatCalibrationProfile(const CalibrationProfile& profile);

// True when every field is equal (doubles exactly).
bool operator==(const CalibrationProfile& a, const CalibrationProfile& b);

}  // namespace cb
