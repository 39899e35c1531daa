// Test helper: a pen source whose samples and connection the test sets, for driving the kiosk's
// screens through a visit. Unplugging behaves like the device backends (drivers/core/
// pen_source.h): the connection becomes `searching` and a proximity-out sample is appended.
#pragma once

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "app/session/synthetic_session.h"
#include "drivers/core/pen_source.h"

namespace cb::test {

class ScriptedPenSource final : public PenSource {
 public:
  ScriptedPenSource(int screen_w, int screen_h)
      : w_(screen_w), h_(screen_h), info_(syntheticTablet(screen_w, screen_h)) {}
  const char* backendName() const override { return "scripted"; }
  void poll(int, std::vector<PenSample>& out) override {
    out.insert(out.end(), queue_.begin(), queue_.end());
    queue_.clear();
  }
  PenConnection connection() const override { return connection_; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override {
    return connection_ == PenConnection::kConnected ? "scripted tablet" : "waiting for a tablet";
  }

  // One hovering sample in proximity at the screen's centre (the visitor picks up the pen).
  void hover(int64_t t_ns) {
    SyntheticStroke s;
    s.control_points = {{float(w_) * 0.5f, float(h_) * 0.5f},
                        {float(w_) * 0.5f + 1.0f, float(h_) * 0.5f}};
    std::vector<PenSample> samples = syntheticPenSamples(s, info_, w_, h_, 200.0, t_ns);
    queue_.push_back(samples.front());  // the first is hovering in proximity
  }
  // A whole stroke (hover, down, lift, out) across the middle of the screen; `lift` false
  // leaves the tip down at its end.
  void stroke(int64_t t_ns, bool lift = true) {
    SyntheticStroke s;
    s.control_points = {{float(w_) * 0.3f, float(h_) * 0.55f},
                        {float(w_) * 0.5f, float(h_) * 0.45f},
                        {float(w_) * 0.7f, float(h_) * 0.55f}};
    s.pressure = [](float t) { return 0.3f + 0.6f * 4.0f * t * (1.0f - t); };
    std::vector<PenSample> samples = syntheticPenSamples(s, info_, w_, h_, 200.0, t_ns);
    if (!lift)
      while (!samples.empty() && !(samples.back().buttons & kPenTip)) samples.pop_back();
    queue_.insert(queue_.end(), samples.begin(), samples.end());
    last_ = samples.back();
  }
  // A tap at `screen_px` (on the screen as the synthetic tablet maps it): hovering in, the tip
  // down for 60 ms, hovering away, at 200 Hz from `t_ns`.
  void tap(glm::dvec2 screen_px, int64_t t_ns) {
    PenSample s{};
    s.x_mm = screen_px.x * double(info_.x_max) / info_.x_res / w_;
    s.y_mm = screen_px.y * double(info_.y_max) / info_.y_res / h_;
    s.x_raw = int32_t(std::lround(s.x_mm * info_.x_res));
    s.y_raw = int32_t(std::lround(s.y_mm * info_.y_res));
    s.tool = PenTool::kPen;
    s.tool_id = 0x802u;
    s.in_proximity = true;
    for (int i = 0; i < 32; ++i, t_ns += 5'000'000) {
      const bool down = i >= 10 && i < 22;
      s.t_ns = t_ns;
      s.pressure_raw = down ? info_.pressure_max * 2 / 5 : 0;
      s.pressure = float(s.pressure_raw) / float(info_.pressure_max);
      s.distance_raw = down ? 0 : 10;
      s.distance = float(s.distance_raw) / float(info_.distance_max);
      s.buttons = down ? kPenTip : 0u;
      queue_.push_back(s);
    }
    last_ = queue_.back();
  }
  // A press at the screen's centre: hovering in, the tip down for `samples` samples at about
  // `level` of the pen's pressure (a small wobble, as a hand holds it), hovering away; 200 Hz.
  void press(float level, int samples, int64_t t_ns) {
    PenSample s{};
    s.x_mm = 0.5 * double(info_.x_max) / info_.x_res;
    s.y_mm = 0.5 * double(info_.y_max) / info_.y_res;
    s.x_raw = int32_t(std::lround(s.x_mm * info_.x_res));
    s.y_raw = int32_t(std::lround(s.y_mm * info_.y_res));
    s.tool = PenTool::kPen;
    s.tool_id = 0x802u;
    s.in_proximity = true;
    for (int i = 0; i < samples + 20; ++i, t_ns += 5'000'000) {
      const bool down = i >= 10 && i < samples + 10;
      const float p = down ? level + 0.004f * float((i % 5) - 2) : 0.0f;
      s.t_ns = t_ns;
      s.pressure_raw = int32_t(std::lround(p * float(info_.pressure_max)));
      s.pressure = float(s.pressure_raw) / float(info_.pressure_max);
      s.distance_raw = down ? 0 : 10;
      s.distance = float(s.distance_raw) / float(info_.distance_max);
      s.buttons = down ? kPenTip : 0u;
      queue_.push_back(s);
    }
    last_ = queue_.back();
  }
  void unplug() {
    connection_ = PenConnection::kSearching;
    PenSample out = last_;
    out.in_proximity = false;
    out.buttons = 0;
    out.pressure = 0.0f;
    out.pressure_raw = 0;
    out.tool = PenTool::kNone;
    queue_.push_back(out);
  }
  void replug() { connection_ = PenConnection::kConnected; }

 private:
  int w_, h_;
  PenDeviceInfo info_;
  PenConnection connection_ = PenConnection::kConnected;
  std::vector<PenSample> queue_;
  PenSample last_{};
};

}  // namespace cb::test
