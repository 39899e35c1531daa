// Wacom tool-id arithmetic of drivers/hid/wacom_wac.c. Which ids are erasers, mice or lens
// cursors is data: config/devices/wacom-tools.toml (a ToolTable, drivers/devices/device_entry.h).
#pragma once

#include <cstdint>

namespace cb::hid {

// The kernel's legacy tool-id form: bits above 0xFFF move up by 4 (wacom_intuos_id_mangle).
inline uint32_t wacomMangleToolId(uint32_t id) {
  return ((id & ~0xFFFu) << 4) | (id & 0xFFFu);
}

}  // namespace cb::hid
