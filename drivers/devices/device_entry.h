// What the device files (config/devices/*.toml, loaded by device_file.h) say about one tablet
// family or model: which kernel driver's rules the decoders mirror, which protocol its pen
// report speaks, its ranges when the protocol does not describe them, the tablet-mode switch,
// the input core's fuzz the kernel driver sets, its tool-id table and report-descriptor
// fix-ups. Plain data (standard library only), so the pure decoders can take it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "drivers/core/pen_sample.h"

namespace cb {

// The kernel driver whose evdev output the HID decoders reproduce.
enum class PenDriverRules : uint8_t {
  kHidInput,  // hid-generic / hid-input (drivers/hid/hid-input.c): every vendor without a file
  kWacom,     // the wacom driver (drivers/hid/wacom_wac.c)
};

// How the pen report is laid out.
enum class PenProtocol : uint8_t {
  kDescriptor,  // the report descriptor names the pen fields (hid_pen_layout.h)
  kIntuos4,     // Wacom's 10-byte report-2 packets (intuos4_decoder.h); ranges from the file
};

// A tool id's kind, as wacom_intuos_get_tool_type() sorts them; ids not listed are pens.
enum class ToolKind : uint8_t { kPen, kEraser, kMouse, kLens };

struct ToolTable {
  std::string name;
  std::map<uint32_t, ToolKind> ids;
  ToolKind kindOf(uint32_t id) const {
    auto it = ids.find(id);
    return it == ids.end() ? ToolKind::kPen : it->second;
  }
  bool isEraser(uint32_t id) const { return kindOf(id) == ToolKind::kEraser; }
  bool isPuck(uint32_t id) const {
    const ToolKind k = kindOf(id);
    return k == ToolKind::kMouse || k == ToolKind::kLens;
  }
};

// The input core's fuzz per axis (input_set_abs_params' fuzz argument), raw device units.
struct AxisFuzz {
  int32_t position = 0;  // ABS_X, ABS_Y
  int32_t tilt = 0;      // ABS_TILT_X, ABS_TILT_Y
  int32_t distance = 0;  // ABS_DISTANCE
  int32_t pressure = 0;  // ABS_PRESSURE
  bool any() const { return position || tilt || distance || pressure; }
};

// A report-descriptor fix-up in the style of a kernel driver's report_fixup(): when the
// descriptor has `size` bytes (0: any size) and holds `expect` at `offset`, those bytes become
// `replace` (same length). hidraw shows the kernel's rewritten descriptor, libusb the device's
// original: applying the fix-up where `expect` still matches gives both backends the same one.
struct ReportFixup {
  size_t size = 0;
  size_t offset = 0;
  std::vector<uint8_t> expect, replace;
  std::string where;  // FILE:LINE of the fix-up, for messages
};

struct DeviceEntry {
  std::string where;   // FILE:LINE:COL of the model (or family) in its file
  std::string family;  // the family's name
  uint16_t vendor = 0;
  std::optional<uint16_t> product;  // absent: every product of the vendor without its own entry
  std::string name;                 // the model's name; empty: the name the device gives
  PenDriverRules rules = PenDriverRules::kHidInput;
  PenProtocol protocol = PenProtocol::kDescriptor;
  PenDeviceInfo
      info{};  // kIntuos4: ranges and resolutions from the file (else from the descriptor)
  uint8_t mode_report_id = 0;  // feature report that selects tablet mode; 0: none
  uint8_t mode_value = 0;
  AxisFuzz fuzz;
  int idle_proximity_timeout_ms = 0;       // 0: no idle-proximity timer
  std::shared_ptr<const ToolTable> tools;  // null: every tool id is a pen
  std::vector<ReportFixup> fixups;
};

// Applies every fix-up whose size and expected bytes match; returns how many applied.
inline int applyReportFixups(const std::vector<ReportFixup>& fixups, std::vector<uint8_t>& desc) {
  int applied = 0;
  for (const ReportFixup& f : fixups) {
    if (f.size != 0 && desc.size() != f.size) continue;
    if (f.offset > desc.size() || desc.size() - f.offset < f.expect.size()) continue;
    bool match = true;
    for (size_t i = 0; i < f.expect.size() && match; ++i) match = desc[f.offset + i] == f.expect[i];
    if (!match) continue;
    for (size_t i = 0; i < f.replace.size(); ++i) desc[f.offset + i] = f.replace[i];
    ++applied;
  }
  return applied;
}

}  // namespace cb
