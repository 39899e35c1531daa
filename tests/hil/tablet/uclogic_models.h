// The UC-Logic tablets the `uclogic` phase plugs in through GadgetFS, as data: identity,
// interfaces and their own report descriptors, the vendor string descriptors hid-uclogic asks
// for, the raw reports the pen sends and what the driver must make of them. One row per init
// path of drivers/hid/hid-uclogic-params.c (Debian's linux-source-6.1): Huion's v2
// (`uclogic_params_huion_init` → `uclogic_params_pen_init_v2`) and XP-Pen/Ugee's v2
// (`uclogic_params_ugee_v2_init`).
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tests/hil/tablet/gadgetfs_device.h"
#include "tests/hil/tablet/hil_checks.h"
#include "tests/hil/tablet/pen_script.h"

namespace cb::hil {

struct UclogicModel {
  std::string name;  // prefixes every check line
  uint16_t vendor = 0, product = 0;
  std::string manufacturer, product_name, serial;
  std::vector<std::vector<uint8_t>> descriptors;  // interface i's own report descriptor
  size_t pen_interface = 0;
  bool magic_out = false;  // the pen interface has an interrupt OUT endpoint
  // The string descriptors beyond 0-3 (index → bytes); every other index stalls.
  std::function<std::optional<std::vector<uint8_t>>(uint8_t index)> vendor_string;
  // Ranges the driver must give (from the parameters served), and its pen report.
  int32_t x_max = 0, y_max = 0, pressure_max = 0, tilt_min = 0, tilt_max = 0;
  bool tilt = true;  // the driver's template has tilt axes
  uint8_t pen_report_id = 0;
  uint32_t x_bits = 0;
  size_t report_bytes = 0;
  std::string pen_node;  // the evdev name hid-uclogic gives the pen
  // The raw report for a step; nullopt: nothing is sent (the driver's timer ends proximity).
  std::function<std::optional<std::vector<uint8_t>>(const PenStep&)> raw_report;
  // What the driver asked of the device (control requests, OUT transfers), checked.
  std::function<void(const std::vector<ControlRecord>&, const std::vector<OutTransfer>&, Checker&)>
      check_requests;
};

UclogicModel huionV2Model(const std::string& fixture_dir);
UclogicModel ugeeV2Model();
UclogicModel ugeeV1Model();

}  // namespace cb::hil
