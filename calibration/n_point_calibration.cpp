#include "calibration/n_point_calibration.h"

#include "drivers/core/toml_number.h"

#include <toml++/toml.h>
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include "calibration/area_mapping.h"
#include "calibration/point_fit.h"

namespace cb {

std::vector<glm::dvec2> targetLayout(int count, int screen_w, int screen_h, double inset) {
  const double x0 = screen_w * inset, x1 = screen_w * (1.0 - inset);
  const double y0 = screen_h * inset, y1 = screen_h * (1.0 - inset);
  const double xc = 0.5 * screen_w, yc = 0.5 * screen_h;
  if (count == 5) return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {xc, yc}};
  std::vector<glm::dvec2> out;
  for (double y : {y0, yc, y1})
    for (double x : {x0, xc, x1}) out.push_back({x, y});
  return out;
}

void TapCollector::down(glm::dvec2 pen_mm) {
  in_contact_ = true;
  points_.clear();
  move(pen_mm);
}

void TapCollector::move(glm::dvec2 pen_mm) {
  if (in_contact_ && std::isfinite(pen_mm.x) && std::isfinite(pen_mm.y)) points_.push_back(pen_mm);
}

std::optional<glm::dvec2> TapCollector::up() {
  if (!in_contact_) return std::nullopt;
  in_contact_ = false;
  // The tap just ended.
  rejection_.clear();
  if (points_.size() < params_.min_samples) {
    rejection_ = "tap too short (" + std::to_string(points_.size()) + " samples)";
    return std::nullopt;
  }
  glm::dvec2 lo = points_[0], hi = points_[0];
  for (const auto& p : points_) lo = glm::min(lo, p), hi = glm::max(hi, p);
  if (glm::length(hi - lo) > params_.max_drag_mm) {
    rejection_ = "the pen moved " + std::to_string(glm::length(hi - lo)) +
                 " mm during the tap: tap and lift without sliding";
    return std::nullopt;
  }
  std::vector<double> xs, ys;
  for (const auto& p : points_) xs.push_back(p.x), ys.push_back(p.y);
  const size_t mid = xs.size() / 2;
  std::nth_element(xs.begin(), xs.begin() + mid, xs.end());
  std::nth_element(ys.begin(), ys.begin() + mid, ys.end());
  return glm::dvec2(xs[mid], ys[mid]);
}

CalibrationFit fitCalibration(const CalibrationProfile& base, const PenDeviceInfo& device,
                              uint64_t tool_serial, int screen_w, int screen_h,
                              const std::vector<Tap>& taps, PointFitKind kind) {
  CalibrationFit out;
  const double w_mm = device.x_res > 0 ? device.x_max / device.x_res : 0.0;
  const double h_mm = device.y_res > 0 ? device.y_max / device.y_res : 0.0;
  const AreaMapping area = computeAreaMapping(base.area, w_mm, h_mm, screen_w, screen_h);
  if (!area.ok) {
    out.error = area.error;
    return out;
  }
  std::vector<glm::dvec2> source, target;
  for (const Tap& t : taps) {
    source.push_back(applyTransform(area.tablet_to_screen, t.pen_mm));
    target.push_back(t.target_px);
  }
  out.fit = fitPoints(kind, source, target);
  if (!out.fit.ok) {
    out.error = out.fit.error;
    return out;
  }
  out.profile = base;
  out.profile.fit_kind = kind;
  out.profile.correction = out.fit.transform;
  out.profile.fit_rms_px = out.fit.rms;
  out.profile.fit_max_px = out.fit.max_residual;
  out.profile.fit_points = static_cast<int>(taps.size());
  out.profile.device.usb_vendor = device.usb_vendor;
  out.profile.device.usb_product = device.usb_product;
  out.profile.device.tool_serial = tool_serial;
  out.profile.device.name = device.name;
  out.ok = true;
  return out;
}

std::string describeFit(const CalibrationFit& fit, const std::vector<Tap>& taps) {
  std::string out = std::string(pointFitKindName(fit.profile.fit_kind)) + " fit over " +
                    std::to_string(taps.size()) + " points:\n";
  char line[160];
  for (size_t i = 0; i < taps.size() && i < fit.fit.residuals.size(); ++i) {
    std::snprintf(line, sizeof line,
                  "  target %zu at (%.0f, %.0f) px: tap at (%.2f, %.2f) mm, residual %.2f px\n", i,
                  taps[i].target_px.x, taps[i].target_px.y, taps[i].pen_mm.x, taps[i].pen_mm.y,
                  fit.fit.residuals[i]);
    out += line;
  }
  std::snprintf(line, sizeof line, "residual: rms %.3f px, max %.3f px", fit.fit.rms,
                fit.fit.max_residual);
  return out + line;
}

std::optional<TapFile> parseTapFile(std::string_view text, const std::string& name,
                                    std::string* error) {
  auto fail = [&](const toml::source_region& where, const std::string& what) {
    if (error) *error = name + ":" + std::to_string(where.begin.line) + ": " + what;
    return std::nullopt;
  };
  auto fail_with = [&](const std::string& message) {
    if (error) *error = message;
    return std::nullopt;
  };
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    return fail(e.source(), std::string(e.description()));
  }
  TapFile f;
  // Numbers through toml_number (no float-to-integer conversion before the range check): a
  // present but refused value says why at its own line, a missing one what is needed.
  std::string why;
  auto integer = [&](const char* table, const char* key, int64_t lo, int64_t hi) {
    const toml::node* n = root[table][key].node();
    return n ? toml_number::integerIn(*n, name, std::string(table) + "." + key, lo, hi, &why)
             : std::nullopt;
  };
  auto number = [&](const char* table, const char* key, double lo, double hi) {
    const toml::node* n = root[table][key].node();
    return n ? toml_number::numberIn(*n, name, std::string(table) + "." + key, lo, hi, &why)
             : std::nullopt;
  };
  auto w = integer("screen", "width", 1, 65536);
  auto h = integer("screen", "height", 1, 65536);
  if (!w || !h) {
    if (!why.empty()) return fail_with(why);
    return fail(root.source(), "[screen] needs integer width and height (1..65536)");
  }
  f.screen_w = static_cast<int>(*w);
  f.screen_h = static_cast<int>(*h);
  auto vendor = integer("device", "usb_vendor", 0, 0xffff);
  auto product = integer("device", "usb_product", 0, 0xffff);
  auto wmm = number("device", "width_mm", 1e-9, 9999.999);
  auto hmm = number("device", "height_mm", 1e-9, 9999.999);
  if (!vendor || !product || !wmm || !hmm) {
    if (!why.empty()) return fail_with(why);
    return fail(root.source(),
                "[device] needs usb_vendor, usb_product (0..0xffff) and width_mm, height_mm "
                "(> 0)");
  }
  f.device.usb_vendor = static_cast<uint16_t>(*vendor);
  f.device.usb_product = static_cast<uint16_t>(*product);
  f.device.x_res = f.device.y_res = 100.0;
  f.device.x_max = static_cast<int32_t>(std::lround(*wmm * 100.0));
  f.device.y_max = static_cast<int32_t>(std::lround(*hmm * 100.0));
  if (auto dn = root["device"]["name"].value<std::string>()) {
    dn->copy(f.device.name, sizeof f.device.name - 1);
  }
  const toml::array* taps = root["tap"].as_array();
  if (!taps) return fail(root.source(), "no [[tap]] entries");
  for (const toml::node& n : *taps) {
    const toml::table* t = n.as_table();
    if (!t) return fail(n.source(), "[[tap]] must be a table");
    const toml::array* tp = (*t)["target_px"].as_array();
    const toml::array* pm = (*t)["pen_mm"].as_array();
    if (!tp || !pm || tp->size() != 2 || pm->size() != 2) {
      return fail(n.source(), "[[tap]] needs target_px = [x, y] and pen_mm = [x, y]");
    }
    Tap tap;
    auto coordinate = [&](const toml::node& c, const char* field) {
      return toml_number::numberIn(c, name, field, -DBL_MAX, DBL_MAX, &why);
    };
    const auto tx = coordinate((*tp)[0], "tap.target_px"),
               ty = coordinate((*tp)[1], "tap.target_px");
    const auto px = coordinate((*pm)[0], "tap.pen_mm"), py = coordinate((*pm)[1], "tap.pen_mm");
    if (!tx || !ty || !px || !py) return fail_with(why);
    tap.target_px = {*tx, *ty};
    tap.pen_mm = {*px, *py};
    f.taps.push_back(tap);
  }
  return f;
}

}  // namespace cb
