// A mouse as the pen when no tablet is connected (X11): pointer events become PenSamples of a
// "mouse" device whose units are screen pixels (0.25 mm each), with a fixed pressure the painter
// can change (−/+ in Paint mode). The samples go through the session like a tablet's, so they
// are journalled and a mouse session replays exactly.
#pragma once

#include <cstdint>

#include "app/render/gl/display.h"
#include "drivers/core/pen_sample.h"

namespace cb {

class MousePen {
 public:
  MousePen(int screen_width, int screen_height);
  const PenDeviceInfo& device() const { return device_; }
  // The sample for a pointer event at t_ns (PointerMove/Down/Up; button 1 is the tip).
  PenSample sample(const DisplayEvent& event, int64_t t_ns);
  // The last sample again at t_ns (the mouse held still: a tablet keeps sending samples).
  PenSample repeat(int64_t t_ns);
  bool down() const { return down_; }
  float pressure() const { return pressure_; }
  void setPressure(float pressure);

 private:
  PenDeviceInfo device_;
  bool down_ = false;
  PenSample last_;
  float pressure_ = 0.6f;
};

}  // namespace cb
