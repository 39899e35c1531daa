// Generic pen-report decoder built from a PenLayout (any digitizer whose descriptor names its
// pen fields, e.g. the Intuos Pro PTH-460/660/860). Mirrors what the kernel's wacom driver
// reports through evdev (wacom_wac_pen_event / wacom_wac_pen_report), so a pen read through
// hidraw or libusb gives the same PenSamples as through evdev.
#pragma once

#include <cstddef>
#include <cstdint>

#include "drivers/core/pen_sample.h"
#include "drivers/hid/decode_result.h"
#include "drivers/hid/hid_pen_layout.h"

namespace cb::hid {

class HidPenDecoder {
 public:
  HidPenDecoder(const PenLayout& layout, const PenDeviceInfo& info)
      : layout_(layout), info_(info) {}

  // Decodes one report as read from hidraw / hid_read (ID byte first when numbered).
  DecodeResult decode(const uint8_t* report, size_t n, int64_t t_ns, PenSample& out);
  // The device went away: returns true and fills `out` with a proximity-out sample if a pen
  // was in proximity.
  bool disconnect(int64_t t_ns, PenSample& out);
  const PenLayout& layout() const { return layout_; }

 private:
  PenLayout layout_;
  PenDeviceInfo info_;
  PenTool tool_ = PenTool::kNone;
  PenSample last_{};
};

}  // namespace cb::hid
