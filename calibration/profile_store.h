// Where calibration profiles live and which one applies to a pen.
//
//   <state_dir>/profiles/<vvvv>-<pppp>-<serial>.toml   the kiosk's own, for one tool
//   <state_dir>/profiles/<vvvv>-<pppp>.toml            the kiosk's own, for the device
//   <config_dir>/profiles/<vvvv>-<pppp>.toml           shipped, for a device model
//   <config_dir>/calibration.toml                      shipped defaults, any device
//   built-in defaults                                  when nothing above loads
//
// The first candidate that exists, parses and matches the device wins. A corrupt candidate is
// reported (file and line) and skipped; a candidate whose [device] names another pen is
// reported and never applied. Directories are parameters: the app passes defaultConfigDir()
// and stateDir() (app/core/config_paths.h); tests pass temporary directories.
#pragma once

#include <string>
#include <vector>

#include "calibration/calibration_profile.h"
#include "drivers/core/pen_sample.h"

namespace cb {

struct ProfileSelection {
  CalibrationProfile profile;         // always usable (built-in defaults at worst)
  std::string source;                 // the file it came from, or "built-in defaults"
  std::vector<std::string> messages;  // errors and skips, for the log and the operator
};

ProfileSelection selectProfile(const PenDeviceInfo& device, uint64_t tool_serial,
                               const std::string& config_dir, const std::string& state_dir);

// The kiosk's profile file for a device (and tool, when serial != 0) under state_dir.
std::string profilePath(const std::string& state_dir, uint16_t usb_vendor, uint16_t usb_product,
                        uint64_t tool_serial);

// Writes the profile atomically (temporary file, then rename), creating directories. The path
// is derived from profile.device (which must name a vendor and product). Returns the path, or
// an empty string with *error set.
std::string saveProfile(const CalibrationProfile& profile, const std::string& state_dir,
                        std::string* error);

}  // namespace cb
