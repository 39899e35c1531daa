// The udev rules that let an unprivileged user (group `input`) open the pens the device files
// name (config/udev/70-cloudbrush-tablet.rules is this text; `cloudbrush devices --udev-rules`
// prints it): tablet event nodes, and per device file the hidraw nodes (the HID device's
// kernel name BUS:VENDOR:PRODUCT.N, any bus: USB, Bluetooth, I2C) and USB devices (libusb) of
// its vendor (a family-wide file) or of each model it lists.
#pragma once

#include <string>

#include "drivers/devices/device_database.h"

namespace cb {

std::string udevRules(const DeviceDatabase& devices);

}  // namespace cb
