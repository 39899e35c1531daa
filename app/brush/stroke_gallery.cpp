#include "app/brush/stroke_gallery.h"

#include <algorithm>
#include <cmath>

#include "app/brush/synthetic_strokes.h"

namespace cb {
namespace {

constexpr double kTabletHz = 200.0;  // an Intuos's report rate, order of magnitude
constexpr double kMouseHz = 125.0;   // a USB mouse
constexpr float kPi = 3.14159265f;

// A pen's pressure over a stroke as calligraphy lays it (thesis §5.1, the "press, move, lift"
// of a brush stroke): a quick attack from `start` to `body`, a plateau, a release to `end`.
auto attackRelease(float start, float body, float end) {
  return [=](float f) {
    if (f < 0.15f) return start + (body - start) * (f / 0.15f);
    if (f > 0.8f) return body + (end - body) * ((f - 0.8f) / 0.2f);
    return body;
  };
}

// A pen held at `at` for `seconds`, its pressure a function of the time fraction, drifting by
// `drift` screen pixels over the hold (a hand never holds perfectly still).
std::vector<BrushInput> held(glm::vec2 at, glm::vec2 drift, double seconds,
                             float (*pressure)(float), float tilt_x, float tilt_y) {
  std::vector<BrushInput> out;
  const int n = std::max(2, int(std::lround(seconds * kTabletHz)));
  for (int k = 0; k <= n; ++k) {
    const float f = float(k) / float(n);
    BrushInput in;
    in.footprint_px = at + drift * f;
    in.pressure = pressure(f);
    in.tilt_x_deg = tilt_x;
    in.tilt_y_deg = tilt_y;
    in.t_ns = int64_t(std::llround(double(k) / kTabletHz * 1e9));
    out.push_back(in);
  }
  return out;
}

GalleryStroke pathStroke(const std::string& name, const SyntheticStroke& s, double hz) {
  return {name, sampleStroke(s, hz), false};
}

// The path strokes, in units of the screen height about the screen's centre (x right, y down).
std::vector<GalleryStroke> pathStrokes(glm::vec2 c, float h) {
  const auto at = [&](float x, float y) { return c + glm::vec2(x, y) * h; };
  std::vector<GalleryStroke> out;
  SyntheticStroke s;
  s.control_points = {at(-0.25f, 0.0f), at(0.25f, 0.0f)};  // 一: across, pressed then lifted
  s.speed_px_s = 0.45f * h;
  s.pressure = attackRelease(0.35f, 0.65f, 0.4f);
  s.tilt_x_deg = [](float) { return 20.0f; };
  out.push_back(pathStroke("horizontal", s, kTabletHz));
  s = {};
  s.control_points = {at(-0.22f, 0.12f), at(-0.05f, -0.12f), at(0.22f, -0.14f)};  // an arc
  s.speed_px_s = 0.5f * h;
  s.pressure = [](float f) { return 0.5f + 0.2f * std::sin(kPi * f); };
  s.tilt_x_deg = [](float f) { return -15.0f + 30.0f * f; };
  out.push_back(pathStroke("bending", s, kTabletHz));
  s = {};
  s.control_points = {at(-0.28f, 0.05f), at(-0.12f, -0.12f), at(0.0f, 0.0f), at(0.12f, 0.12f),
                      at(0.28f, -0.05f)};
  s.speed_px_s = 0.6f * h;
  s.pressure = [](float f) { return 0.55f + 0.2f * std::sin(2.0f * kPi * f); };
  out.push_back(pathStroke("s_curve", s, kTabletHz));
  s = {};
  s.control_points = {at(0.02f, -0.22f), at(0.02f, 0.15f), at(-0.02f, 0.2f), at(-0.12f, 0.12f)};
  s.speed_px_s = 0.55f * h;
  s.pressure = [](float f) { return f < 0.7f ? 0.7f : 0.7f - 0.9f * (f - 0.7f); };  // 亅
  s.tilt_y_deg = [](float) { return 15.0f; };
  out.push_back(pathStroke("hook", s, kTabletHz));
  s = {};
  for (int k = 0; k <= 8; ++k)
    s.control_points.push_back(at(-0.25f + 0.5f * float(k) / 8.0f, (k % 2 ? 0.08f : -0.08f)));
  s.speed_px_s = 1.2f * h;
  s.pressure = [](float) { return 0.6f; };
  out.push_back(pathStroke("scribble", s, kTabletHz));
  s = {};
  s.control_points = {at(-0.25f, 0.1f), at(0.25f, -0.1f)};
  s.speed_px_s = 5000.0f;  // a flick: 3 m/s on a tablet, 5,000 px/s with a mouse
  s.pressure = [](float f) { return 0.7f - 0.3f * f; };
  out.push_back(pathStroke("fast_flick", s, kTabletHz));
  s = {};
  s.control_points = {at(-0.15f, 0.0f), at(0.15f, 0.02f)};
  s.speed_px_s = 0.08f * h;
  s.pressure = [](float f) { return 0.3f + 0.7f * f; };  // pressed harder and harder
  out.push_back(pathStroke("slow_press", s, kTabletHz));
  s = {};
  s.control_points = {at(-0.22f, 0.05f), at(0.0f, -0.02f), at(0.22f, 0.04f)};
  s.speed_px_s = 0.5f * h;
  s.pressure = [](float) { return 0.2f; };
  out.push_back(pathStroke("light_touch", s, kTabletHz));
  s = {};
  s.control_points = {at(-0.24f, 0.0f), at(0.24f, 0.0f)};
  s.speed_px_s = 0.4f * h;
  s.pressure = [](float) { return 0.7f; };
  s.tilt_x_deg = [](float) { return 55.0f; };  // the brush laid on its side
  s.tilt_y_deg = [](float) { return 20.0f; };
  out.push_back(pathStroke("tilted_side", s, kTabletHz));
  s = {};
  s.control_points = {at(-0.25f, 0.08f), at(-0.08f, -0.03f), at(0.08f, 0.03f), at(0.25f, -0.08f)};
  s.speed_px_s = 800.0f;
  s.pressure = [](float) { return 0.6f; };  // the mouse's fixed pressure (mouse_pen.h)
  out.push_back(pathStroke("mouse", s, kMouseHz));
  return out;
}

}  // namespace

std::vector<GalleryStroke> strokeGallery(int w, int h) {
  const glm::vec2 c(0.5f * float(w), 0.5f * float(h));
  const float hf = float(h);
  std::vector<GalleryStroke> out;
  out.push_back({"dot",
                 held(
                     c, glm::vec2(0.004f, 0.003f) * hf, 0.3,
                     [](float f) { return 0.25f + 0.5f * std::sin(kPi * f); }, 10.0f, 10.0f),
                 true});
  for (GalleryStroke& s : pathStrokes(c, hf)) out.push_back(std::move(s));
  out.push_back(
      {"dab",
       held(
           c, glm::vec2(0.03f, 0.01f) * hf, 0.12,
           [](float f) { return 0.9f * std::sin(kPi * std::min(1.0f, 0.2f + f)); }, -25.0f, 5.0f),
       true});
  return out;
}

std::vector<BrushInput> scaledSamples(const std::vector<BrushInput>& samples, glm::vec2 scale) {
  std::vector<BrushInput> out = samples;
  for (BrushInput& in : out) in.footprint_px *= scale;
  return out;
}

}  // namespace cb
