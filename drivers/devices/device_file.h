// Loads the device files (config/devices/*.toml): one tablet family per file, its models, its
// quirks and tool-id tables (format: config/devices/README.md). Every mistake is reported as
// FILE:LINE:COL: key: what, and a file with a mistake adds nothing (the others still load).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "drivers/devices/device_database.h"

namespace cb {

struct DeviceFileLoad {
  std::shared_ptr<const DeviceDatabase> database;  // never null
  std::vector<std::string> errors;
};

// Every *.toml in `dir`, in name order. A missing folder is an error; an empty one is not.
DeviceFileLoad loadDeviceDirectory(const std::string& dir);
// Files given as (name, text) pairs, e.g. by tests and the fuzz target. Tool tables may be
// named by a family in any of the files.
DeviceFileLoad parseDeviceFiles(const std::vector<std::pair<std::string, std::string>>& files);

}  // namespace cb
