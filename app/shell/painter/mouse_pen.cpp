#include "app/shell/painter/mouse_pen.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cb {
namespace {

constexpr double kUnitsPerMm = 4.0;  // a pixel is 0.25 mm, about a desktop monitor's pitch
constexpr int32_t kPressureMax = 1023;

}  // namespace

MousePen::MousePen(int screen_width, int screen_height) {
  std::strncpy(device_.name, "mouse (no tablet)", sizeof device_.name - 1);
  device_.x_max = std::max(1, screen_width - 1);
  device_.y_max = std::max(1, screen_height - 1);
  device_.x_res = device_.y_res = kUnitsPerMm;
  device_.pressure_max = kPressureMax;
}

void MousePen::setPressure(float pressure) {
  pressure_ = std::clamp(pressure, 0.05f, 1.0f);
}

PenSample MousePen::sample(const DisplayEvent& event, int64_t t_ns) {
  if (event.button == 1 && event.kind == DisplayEvent::Kind::PointerDown) down_ = true;
  if (event.button == 1 && event.kind == DisplayEvent::Kind::PointerUp) down_ = false;
  PenSample s;
  s.t_ns = t_ns;
  s.x_raw = std::clamp(int32_t(std::lround(event.x)), 0, device_.x_max);
  s.y_raw = std::clamp(int32_t(std::lround(event.y)), 0, device_.y_max);
  s.x_mm = s.x_raw / kUnitsPerMm;
  s.y_mm = s.y_raw / kUnitsPerMm;
  s.pressure_raw = down_ ? int32_t(std::lround(pressure_ * kPressureMax)) : 0;
  s.pressure = float(s.pressure_raw) / float(kPressureMax);
  s.buttons = down_ ? kPenTip : 0u;
  s.tool = PenTool::kPen;
  s.in_proximity = true;
  last_ = s;
  return s;
}

PenSample MousePen::repeat(int64_t t_ns) {
  last_.t_ns = t_ns;
  return last_;
}

}  // namespace cb
