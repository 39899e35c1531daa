// Finds pen devices among /dev/input/event* (BTN_TOOL_PEN + ABS_X/ABS_Y; pressure optional, as
// a tip-switch-only pen has none), Wacom (056a) first.
#pragma once

#include <string>
#include <vector>

#include "drivers/core/pen_sample.h"

struct libevdev;

namespace cb {

struct EvdevPenCandidate {
  std::string path;
  PenDeviceInfo info;
  bool permission_denied = false;  // exists but cannot be opened by this user
};

// Scans `dir` (default /dev/input) for pen event nodes. Nodes that cannot be opened for lack of
// permission are listed with permission_denied set (so the caller can name the udev rule).
std::vector<EvdevPenCandidate> findEvdevPens(const std::string& dir = "/dev/input");

// True when the device reports a pen: BTN_TOOL_PEN, ABS_X and ABS_Y.
bool isEvdevPen(libevdev* dev);
// Ranges and units from the device's absinfo (resolutions: units/mm; tilt converted from the
// kernel's units per radian to units per degree).
PenDeviceInfo evdevPenInfo(libevdev* dev);

}  // namespace cb
