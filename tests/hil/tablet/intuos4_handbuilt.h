// A HAND-BUILT report descriptor for an Intuos4 (no descriptor of a real Intuos4 is available).
// It declares what the kernel's wacom driver needs to drive the Intuos4 protocol
// (drivers/hid/wacom_wac.c, wacom_intuos_irq): a pen application collection with input report 2
// of 9 opaque bytes (10-byte packets with the ID) and feature report 2, the mode report that
// switches the tablet to the full protocol when set to 2.
#pragma once

#include <cstdint>
#include <vector>

namespace cb::hil {

inline const std::vector<uint8_t>& handBuiltIntuos4Descriptor() {
  static const std::vector<uint8_t> kDescriptor = {
      0x05, 0x0D,        // Usage Page (Digitizer)
      0x09, 0x02,        // Usage (Pen)
      0xA1, 0x01,        // Collection (Application)
      0x85, 0x02,        //   Report ID (2)
      0x09, 0x20,        //   Usage (Stylus)
      0xA1, 0x00,        //   Collection (Physical)
      0x06, 0x0D, 0xFF,  //     Usage Page (Wacom vendor 0xFF0D)
      0x09, 0x01,        //     Usage (0x01): the packet bytes, decoded by the driver
      0x15, 0x00,        //     Logical Minimum (0)
      0x26, 0xFF, 0x00,  //     Logical Maximum (255)
      0x75, 0x08,        //     Report Size (8)
      0x95, 0x09,        //     Report Count (9)
      0x81, 0x02,        //     Input (Data, Variable, Absolute)
      0x09, 0x02,        //     Usage (0x02): tablet mode
      0x95, 0x01,        //     Report Count (1)
      0xB1, 0x02,        //     Feature (Data, Variable, Absolute)
      0xC0,              //   End Collection
      0xC0,              // End Collection
  };
  return kDescriptor;
}

}  // namespace cb::hil
