// Fuzz target: the device-file loader (config/devices/*.toml are edited by hand and passed
// around like libinput quirks). Either the file loads and every entry is consistent, or each
// error names the file with a line and column, and the file adds nothing.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "drivers/devices/device_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const cb::DeviceFileLoad load = cb::parseDeviceFiles({{"fuzz.toml", text}});
  if (!load.database) std::abort();
  for (const std::string& e : load.errors)
    if (e.rfind("fuzz.toml:", 0) != 0) std::abort();
  if (!load.errors.empty() && !load.database->entries().empty()) std::abort();
  for (const cb::DeviceEntry& e : load.database->entries()) {
    if (e.protocol == cb::PenProtocol::kIntuos4 &&
        (e.info.x_max <= 0 || e.info.y_max <= 0 || e.info.pressure_max <= 0 || !e.product))
      std::abort();
    for (const cb::ReportFixup& f : e.fixups)
      if (f.expect.size() != f.replace.size() || f.expect.empty()) std::abort();
    if (load.database->find(e.vendor, e.product.value_or(0)) == nullptr) std::abort();
  }
  return 0;
}
