// The device files (config/devices) as the guest has them (copied to /hil/devices), and hidapi
// source options that use them, for every phase of the virtual tablet test.
#pragma once

#include <cstdint>
#include <memory>

#include "drivers/devices/device_database.h"
#include "drivers/hid/hidapi_pen_source.h"

namespace cb::hil {

inline std::shared_ptr<const DeviceDatabase>& hilDevices() {
  static std::shared_ptr<const DeviceDatabase> db = std::make_shared<DeviceDatabase>();
  return db;
}

inline hid::HidapiPenSourceOptions hidOptions(hid::HidapiBackend backend, uint16_t vendor) {
  hid::HidapiPenSourceOptions o;
  o.backend = backend;
  o.vendor = vendor;
  o.devices = hilDevices();
  return o;
}

}  // namespace cb::hil
