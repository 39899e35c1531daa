#include "calibration/area_mapping.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cb {
namespace {

glm::dmat3 translation(double x, double y) {
  glm::dmat3 m(1.0);
  m[2][0] = x;
  m[2][1] = y;
  return m;
}

glm::dmat3 scaling(double sx, double sy) {
  glm::dmat3 m(1.0);
  m[0][0] = sx;
  m[1][1] = sy;
  return m;
}

// Clockwise on the desk = clockwise on a y-down screen: (x, y) -> (x c - y s, x s + y c).
glm::dmat3 rotation(double deg) {
  const double r = deg * std::numbers::pi / 180.0;
  double c = std::cos(r), s = std::sin(r);
  // Exact quarter turns, so 90° steps do not carry 1e-17 shears.
  if (std::abs(c) < 1e-15) c = 0.0;
  if (std::abs(s) < 1e-15) s = 0.0;
  glm::dmat3 m(1.0);
  m[0][0] = c;
  m[0][1] = s;
  m[1][0] = -s;
  m[1][1] = c;
  return m;
}

bool finiteRect(const RectD& r) {
  return std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.w) && std::isfinite(r.h);
}

}  // namespace

const char* areaFitName(AreaFit fit) {
  switch (fit) {
    case AreaFit::kStretch:
      return "stretch";
    case AreaFit::kFit:
      return "fit";
    case AreaFit::kLetterbox:
      return "letterbox";
    case AreaFit::kDisplay:
      return "display";
  }
  return "fit";
}

bool parseAreaFit(const std::string& text, AreaFit* out) {
  if (text == "stretch")
    *out = AreaFit::kStretch;
  else if (text == "fit")
    *out = AreaFit::kFit;
  else if (text == "letterbox")
    *out = AreaFit::kLetterbox;
  else if (text == "display")
    *out = AreaFit::kDisplay;
  else
    return false;
  return true;
}

AreaMapping computeAreaMapping(const AreaMappingConfig& config, double tablet_w_mm,
                               double tablet_h_mm, double screen_w_px, double screen_h_px) {
  AreaMapping out;
  if (!(tablet_w_mm > 0 && tablet_h_mm > 0 && std::isfinite(tablet_w_mm) &&
        std::isfinite(tablet_h_mm))) {
    out.error = "area mapping: the tablet's active area is empty (" + std::to_string(tablet_w_mm) +
                " x " + std::to_string(tablet_h_mm) + " mm)";
    return out;
  }
  if (!(screen_w_px > 0 && screen_h_px > 0)) {
    out.error = "area mapping: the screen is empty";
    return out;
  }
  const bool display = config.fit == AreaFit::kDisplay;
  RectD area{0, 0, tablet_w_mm, tablet_h_mm};
  if (config.tablet_area_mm && !display) {
    area = *config.tablet_area_mm;
    if (!finiteRect(area) || area.w <= 0 || area.h <= 0 || area.x < -1e-9 || area.y < -1e-9 ||
        area.x + area.w > tablet_w_mm + 1e-9 || area.y + area.h > tablet_h_mm + 1e-9) {
      out.error = "area mapping: tablet area [" + std::to_string(area.x) + ", " +
                  std::to_string(area.y) + ", " + std::to_string(area.w) + ", " +
                  std::to_string(area.h) + "] mm is not inside the active area " +
                  std::to_string(tablet_w_mm) + " x " + std::to_string(tablet_h_mm) + " mm";
      return out;
    }
  }
  RectD region{0, 0, screen_w_px, screen_h_px};
  if (config.screen_region_px) {
    region = *config.screen_region_px;
    if (!finiteRect(region) || region.w <= 0 || region.h <= 0) {
      out.error = "area mapping: the screen region is empty or not finite";
      return out;
    }
  }
  if (!std::isfinite(config.rotation_deg)) {
    out.error = "area mapping: rotation is not finite";
    return out;
  }

  // Half sizes of the area and the turned frame's sines.
  const double a = area.w / 2, b = area.h / 2;
  const double r = config.rotation_deg * std::numbers::pi / 180.0;
  const double c = std::abs(std::cos(r)), s = std::abs(std::sin(r));
  const bool quarter_turned = s > c;  // nearer to 90° or 270°: width and height swap
  const double area_aspect = quarter_turned ? b / a : a / b;

  // Aspect of the usable rectangle in the turned frame.
  double aspect = area_aspect;
  if (config.fit == AreaFit::kFit) aspect = region.w / region.h;
  // Largest centred axis-aligned rectangle (half sizes w, w/aspect) inside the turned area:
  //   w c + h s <= a,  w s + h c <= b.
  const double hw = std::min(a / (c + s / aspect), b / (s + c / aspect));
  const double hh = hw / aspect;

  RectD target = region;
  if (config.fit == AreaFit::kLetterbox) {
    const double k = std::min(region.w / (2 * hw), region.h / (2 * hh));
    target.w = 2 * hw * k;
    target.h = 2 * hh * k;
    target.x = region.x + (region.w - target.w) / 2;
    target.y = region.y + (region.h - target.h) / 2;
  }
  // mm -> centred -> turned -> scaled to the target rectangle -> placed.
  out.tablet_to_screen = translation(target.x + target.w / 2, target.y + target.h / 2) *
                         scaling(target.w / (2 * hw), target.h / (2 * hh)) *
                         rotation(config.rotation_deg) * translation(-(area.x + a), -(area.y + b));
  out.used_region_px = target;
  out.ok = true;
  return out;
}

}  // namespace cb
