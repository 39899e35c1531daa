#include "calibration/calibrator.h"

#include <cmath>
#include <numbers>

#include "calibration/area_mapping.h"
#include "calibration/point_fit.h"
#include "calibration/tilt.h"

namespace cb {

Calibrator::Calibrator(const CalibrationProfile& profile, const PenDeviceInfo& device,
                       int screen_w_px, int screen_h_px)
    : profile_(profile),
      device_(device),
      nib_(profile.pressure.nib),
      contact_(profile.pressure.contact),
      curve_(profile.pressure.curve),
      position_filter_(profile.smoothing.position),
      tilt_filter_(profile.smoothing.tilt),
      predictor_(profile.prediction) {
  const double w_mm = device.x_res > 0 ? device.x_max / device.x_res : 0.0;
  const double h_mm = device.y_res > 0 ? device.y_max / device.y_res : 0.0;
  AreaMapping m = computeAreaMapping(profile.area, w_mm, h_mm, screen_w_px, screen_h_px);
  if (!m.ok) {
    error_ = m.error;
    AreaMappingConfig whole = profile.area;
    whole.tablet_area_mm.reset();
    whole.screen_region_px.reset();
    m = computeAreaMapping(whole, w_mm, h_mm, screen_w_px, screen_h_px);
    if (!m.ok) error_ += "; " + m.error;
  }
  area_transform_ = m.tablet_to_screen;
  tablet_to_screen_ = profile.fit_kind == PointFitKind::kNone
                          ? area_transform_
                          : profile.correction * area_transform_;
}

void Calibrator::resetFilters() {
  position_filter_.reset();
  tilt_filter_.reset();
  predictor_.reset();
}

MappedSample Calibrator::process(const PenSample& s) {
  MappedSample out;
  out.raw = s;
  out.t_ns = s.t_ns;
  out.in_proximity = s.in_proximity;

  if (s.in_proximity && !in_proximity_) {
    out.proximity_began = true;
    nib_.proximityIn();
    resetFilters();
  }
  const bool was_down = contact_.down();
  if (!s.in_proximity) {
    contact_.reset();
  } else {
    nib_.observe(s, device_.distance_max > 0);
    if (device_.pressure_max > 0) {
      contact_.update(nib_.correct(s.pressure));
    } else if (s.tipDown() != contact_.down()) {
      // A pen without pressure: the device's own contact bit is all there is.
      contact_.update(s.tipDown() ? 1.0f : 0.0f);
    }
  }
  in_proximity_ = s.in_proximity;
  out.contact = contact_.down();
  out.contact_began = out.contact && !was_down;
  out.contact_ended = !out.contact && was_down;
  if (out.contact_began) resetFilters();

  // Pressure: offset -> participant range -> curve.
  const float corrected = nib_.correct(s.pressure);
  out.pressure_corrected = s.in_proximity ? corrected : 0.0f;
  out.pressure = out.contact ? curve_.apply(range_.apply(corrected)) : 0.0f;
  out.light_contact =
      out.contact && device_.pressure_max > 0 && corrected < contact_.thresholds().down;

  // Position.
  double x = s.x_mm, y = s.y_mm;
  if (!std::isfinite(x) || !std::isfinite(y)) {
    ++rejected_;
    x = last_x_mm_;
    y = last_y_mm_;
  }
  last_x_mm_ = x;
  last_y_mm_ = y;
  const auto filtered = position_filter_.filter({x, y}, s.t_ns);
  const double lag_s = 1.0 / (2.0 * std::numbers::pi * position_filter_.lastCutoffHz());
  const auto predicted = predictor_.predict(filtered, s.t_ns, lag_s);
  const glm::dvec2 px = applyTransform(tablet_to_screen_, {filtered[0], filtered[1]});
  const glm::dvec2 pv = applyTransform(tablet_to_screen_, {predicted[0], predicted[1]});
  out.x_px = px.x;
  out.y_px = px.y;
  out.preview_x_px = pv.x;
  out.preview_y_px = pv.y;

  // Tilt.
  const double tx = std::isfinite(s.tilt_x_deg) ? s.tilt_x_deg - profile_.tilt_zero.x_deg : 0.0;
  const double ty = std::isfinite(s.tilt_y_deg) ? s.tilt_y_deg - profile_.tilt_zero.y_deg : 0.0;
  const auto tilt = tilt_filter_.filter({tx, ty}, s.t_ns);
  out.tilt_x_deg = static_cast<float>(tilt[0]);
  out.tilt_y_deg = static_cast<float>(tilt[1]);
  const TiltAngles angles = tiltToAzimuthAltitude(out.tilt_x_deg, out.tilt_y_deg);
  out.azimuth_deg = angles.azimuth_deg;
  out.altitude_deg = angles.altitude_deg;
  return out;
}

}  // namespace cb
