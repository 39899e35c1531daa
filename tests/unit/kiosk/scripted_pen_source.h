// Test helper: a pen source whose samples and connection the test sets, for driving the kiosk's
// screens through a visit. Unplugging behaves like the device backends (drivers/core/
// pen_source.h): the connection becomes `searching` and a proximity-out sample is appended.
#pragma once

#include <vector>

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
