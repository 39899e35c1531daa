#include "app/session/synthetic_session.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cb {
namespace {

constexpr double kUnitsPerMm = 200.0;  // 0.005 mm per unit
constexpr double kMmPerScreenPixel = 0.2;
constexpr int32_t kPressureMax = 8191;
constexpr double kHoverSeconds = 0.05, kTailSeconds = 0.03;

}  // namespace

PenDeviceInfo syntheticTablet(int screen_width, int screen_height) {
  PenDeviceInfo info;
  info.usb_vendor = 0x056a;  // shaped like a Wacom pen, with a product id no pen uses
  info.usb_product = 0xfff0;
  std::strncpy(info.name, "cloudbrush synthetic tablet", sizeof info.name - 1);
  info.x_max = int32_t(std::lround(screen_width * kMmPerScreenPixel * kUnitsPerMm));
  info.y_max = int32_t(std::lround(screen_height * kMmPerScreenPixel * kUnitsPerMm));
  info.x_res = info.y_res = kUnitsPerMm;
  info.pressure_max = kPressureMax;
  info.tilt_min = -64;
  info.tilt_max = 63;
  info.tilt_res = 0.0;  // raw tilt is in degrees
  info.distance_max = 63;
  return info;
}

std::vector<PenSample> syntheticPenSamples(const SyntheticStroke& stroke,
                                           const PenDeviceInfo& tablet, int screen_width,
                                           int screen_height, double rate_hz, int64_t t0_ns) {
  const std::vector<BrushInput> inputs = sampleStroke(stroke, rate_hz, 0);
  std::vector<PenSample> samples;
  if (inputs.empty()) return samples;
  const double sx = double(tablet.x_max) / tablet.x_res / screen_width;
  const double sy = double(tablet.y_max) / tablet.y_res / screen_height;
  const int64_t period_ns = int64_t(std::llround(1e9 / rate_hz));
  const auto make = [&](const BrushInput& in, int64_t t_ns, float pressure, bool tip,
                        bool proximity) {
    PenSample s;
    s.t_ns = t_ns;
    s.x_mm = in.footprint_px.x * sx;
    s.y_mm = in.footprint_px.y * sy;
    s.x_raw = int32_t(std::lround(s.x_mm * tablet.x_res));
    s.y_raw = int32_t(std::lround(s.y_mm * tablet.y_res));
    s.pressure_raw = int32_t(std::lround(std::clamp(pressure, 0.0f, 1.0f) * tablet.pressure_max));
    s.pressure = float(s.pressure_raw) / float(tablet.pressure_max);
    s.tilt_x_raw = int32_t(std::lround(in.tilt_x_deg));
    s.tilt_y_raw = int32_t(std::lround(in.tilt_y_deg));
    s.tilt_x_deg = float(s.tilt_x_raw);
    s.tilt_y_deg = float(s.tilt_y_raw);
    s.distance_raw = tip ? 0 : 10;
    s.distance = float(s.distance_raw) / float(tablet.distance_max);
    s.buttons = tip ? kPenTip : 0u;
    s.tool = proximity ? PenTool::kPen : PenTool::kNone;
    s.tool_id = proximity ? 0x802u : 0u;
    s.in_proximity = proximity;
    return s;
  };
  int64_t t = t0_ns;
  const int hover = std::max(1, int(kHoverSeconds * rate_hz));
  for (int i = 0; i < hover; ++i, t += period_ns)
    samples.push_back(make(inputs.front(), t, 0.0f, false, true));
  for (const BrushInput& in : inputs) {
    samples.push_back(make(in, t0_ns + hover * period_ns + in.t_ns, in.pressure, true, true));
  }
  t = samples.back().t_ns + period_ns;
  const int tail = std::max(1, int(kTailSeconds * rate_hz));
  for (int i = 0; i < tail; ++i, t += period_ns)
    samples.push_back(make(inputs.back(), t, 0.0f, false, true));
  samples.push_back(make(inputs.back(), t, 0.0f, false, false));
  return samples;
}

std::vector<SyntheticStroke> referencePaintStrokes(int screen_width, int screen_height) {
  return {gentleCurve(screen_width, screen_height), pressureRamp(screen_width, screen_height)};
}

}  // namespace cb
