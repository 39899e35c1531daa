// Generic pen-report decoder built from a PenLayout (any digitizer whose descriptor names its
// pen fields). It reports what the kernel driver bound to the device reports through evdev, so a
// pen read through hidraw or libusb gives the same PenSamples as through evdev:
// - the wacom driver (config/devices/wacom-generic.toml: USB vendor 056a): its generic pen path
// (wacom_wac_pen_event /
//   wacom_wac_pen_report): the tool is chosen on entering range (Invert or an eraser tool id),
//   contact is Tip Switch or Eraser, serial and tool id from Wacom's vendor usages;
// - everyone else: hid-input's rules (drivers/hid/hid-input.c, hidinput_hid_event): values of
//   a Null State field outside the logical range are ignored (the previous value stays), other
//   values are clamped to the logical range, and the tool follows HidInputToolState.
#pragma once

#include <cstddef>
#include <cstdint>

#include <memory>

#include "drivers/core/pen_sample.h"
#include "drivers/devices/device_entry.h"
#include "drivers/hid/decode_result.h"
#include "drivers/hid/hid_input_key.h"
#include "drivers/hid/hid_input_tool_state.h"
#include "drivers/hid/hid_pen_layout.h"

namespace cb::hid {

class HidPenDecoder {
 public:
  // `rules` and `tools` (Wacom rules: which tool ids are erasers) come from the device files
  // (DeviceDatabase); a device without an entry has hid-input's rules.
  HidPenDecoder(const PenLayout& layout, const PenDeviceInfo& info,
                PenDriverRules rules = PenDriverRules::kHidInput,
                std::shared_ptr<const ToolTable> tools = nullptr);

  // Decodes one report as read from hidraw / hid_read (ID byte first when numbered).
  DecodeResult decode(const uint8_t* report, size_t n, int64_t t_ns, PenSample& out);
  // The device went away: returns true and fills `out` with a proximity-out sample if a pen
  // was in proximity.
  bool disconnect(int64_t t_ns, PenSample& out);
  const PenLayout& layout() const { return layout_; }
  PenDriverRules rules() const { return rules_; }

 private:
  DecodeResult decodeWacom(const uint8_t* p, size_t pn, int64_t t_ns, PenSample& out);
  DecodeResult decodeHidInput(const uint8_t* p, size_t pn, int64_t t_ns, PenSample& out);
  DecodeResult proximityOut(int64_t t_ns, PenSample& out);
  void updateKeys(const uint8_t* p, size_t pn);

  PenLayout layout_;
  PenDeviceInfo info_;
  PenDriverRules rules_;
  std::shared_ptr<const ToolTable> tools_;
  PenTool tool_ = PenTool::kNone;  // Wacom rules: the tool chosen on entering range
  HidInputToolState hid_input_;    // hid-input rules
  HidInputKey<2> stylus2_;         // hid-input rules: Secondary Barrel Switch, Tablet Pick
  HidInputKey<2> other_touch_;     // hid-input rules: Touch, Secondary Tip Switch
  PenSample state_{};              // hid-input rules: the axis values evdev holds
  PenSample last_{};
};

}  // namespace cb::hid
