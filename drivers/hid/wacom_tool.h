// Wacom tool ids (the value the kernel reports as ABS_MISC), as drivers/hid/wacom_wac.c
// classifies them in wacom_intuos_get_tool_type().
#pragma once

#include <cstdint>

#include "drivers/core/pen_sample.h"

namespace cb::hid {

// Eraser ends of Wacom pens; every other stylus id is a pen tip.
inline bool wacomToolIsEraser(uint32_t id) {
  switch (id) {
    case 0x82a:
    case 0x84a:
    case 0x85a:
    case 0x91a:
    case 0xd1a:
    case 0x0fa:
    case 0x82b:
    case 0x81b:
    case 0x91b:
    case 0x80c:
    case 0x80a:
    case 0x90a:
    case 0x1480a:
    case 0x1090a:
    case 0x1080c:
    case 0x1084a:
    case 0x1680a:
    case 0x1880a:
    case 0x1080a:
      return true;
    default:
      return false;
  }
}

// Mice and lens cursors (BTN_TOOL_MOUSE, BTN_TOOL_LENS in wacom_intuos_get_tool_type).
inline bool wacomToolIsPuck(uint32_t id) {
  switch (id) {
    case 0x007:
    case 0x09c:
    case 0x094:
    case 0x017:
    case 0x806:
    case 0x096:
    case 0x097:
    case 0x006:
      return true;
    default:
      return false;
  }
}

// The kernel's legacy tool-id form: bits above 0xFFF move up by 4 (wacom_intuos_id_mangle).
inline uint32_t wacomMangleToolId(uint32_t id) {
  return ((id & ~0xFFFu) << 4) | (id & 0xFFFu);
}

}  // namespace cb::hid
