#include "calibration/pressure_range.h"

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include "drivers/core/toml_number.h"

namespace cb {
namespace {

constexpr size_t kMinSamples = 10;  // 50 ms at 200 Hz
constexpr float kMinSpan = 0.05f;   // firm must exceed light by 5 % of the range

float quantile(std::vector<float>& v, double q) {
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

void dropNonFinite(std::vector<float>& v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](float p) { return !std::isfinite(p); }), v.end());
}

}  // namespace

float PressureRange::apply(float pressure) const {
  if (!std::isfinite(pressure)) return 0.0f;
  if (hi <= lo) return pressure >= hi ? 1.0f : 0.0f;
  return std::clamp((pressure - lo) / (hi - lo), 0.0f, 1.0f);
}

PressureRangeFit fitPressureRange(std::vector<float> light, std::vector<float> firm,
                                  float light_target) {
  PressureRangeFit fit;
  dropNonFinite(light);
  dropNonFinite(firm);
  if (light.size() < kMinSamples || firm.size() < kMinSamples) {
    fit.error = "too few samples in contact (light " + std::to_string(light.size()) + ", firm " +
                std::to_string(firm.size()) + ", need " + std::to_string(kMinSamples) +
                " each): hold the pen down a little longer";
    return fit;
  }
  fit.light = quantile(light, 0.5);
  fit.firm = quantile(firm, 0.9);
  if (fit.firm - fit.light < kMinSpan) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "firm press (%.3f) is not firmer than the light press (%.3f): press harder",
                  fit.firm, fit.light);
    fit.error = buf;
    return fit;
  }
  light_target = std::clamp(light_target, 0.0f, 0.9f);
  PressureRange r;
  r.hi = std::clamp(fit.firm, kMinSpan, 1.0f);
  r.lo = std::max(0.0f, (fit.light - light_target * r.hi) / (1.0f - light_target));
  fit.range = r;
  return fit;
}

void PressureRangeCollector::feed(bool contact, float pressure) {
  if (step_ == Step::kDone) return;
  if (contact) {
    if (std::isfinite(pressure)) current_.push_back(pressure);
    return;
  }
  // Lifted: a step counts once the press was held long enough; shorter presses start over.
  if (current_.size() >= hold_samples_) {
    if (step_ == Step::kLight) {
      light_ = std::move(current_);
      step_ = Step::kFirm;
    } else {
      result_ = fitPressureRange(light_, current_, light_target_);
      step_ = Step::kDone;
    }
  }
  current_.clear();
}

void PressureRangeCollector::restart() {
  step_ = Step::kLight;
  current_.clear();
  light_.clear();
  result_ = PressureRangeFit{};
}

std::string pressureRangeToToml(const PressureRange& range) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[pressure_range]\nlo = %.9g\nhi = %.9g\n", range.lo, range.hi);
  return buf;
}

std::optional<PressureRange> pressureRangeFromToml(const std::string& text, std::string* error,
                                                   std::string_view name) {
  try {
    toml::table t = toml::parse(text, std::string(name));
    std::string why;
    auto number = [&](const char* key) -> std::optional<double> {
      const toml::node* n = t["pressure_range"][key].node();
      return n ? toml_number::numberIn(*n, name, std::string("pressure_range.") + key, 0.0, 1.0,
                                       &why)
               : std::nullopt;
    };
    const auto lo = number("lo"), hi = number("hi");
    if (!lo || !hi || *lo >= *hi) {
      if (error) *error = !why.empty() ? why : "[pressure_range] needs numbers 0 <= lo < hi <= 1";
      return std::nullopt;
    }
    return PressureRange{static_cast<float>(*lo), static_cast<float>(*hi)};
  } catch (const toml::parse_error& e) {
    if (error) {
      *error = (name.empty() ? "line " : std::string(name) + ":") +
               std::to_string(e.source().begin.line) + ": " + std::string(e.description());
    }
    return std::nullopt;
  }
}

}  // namespace cb
