// Test data shared by the driver tests: the real Wacom descriptors in tests/fixtures/hid
// (CB_HID_FIXTURE_DIR, set by cb_add_test) and the shipped device files (config/devices).
#pragma once

#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "drivers/devices/device_file.h"

namespace cb::test {

inline std::vector<uint8_t> readFixture(const std::string& name) {
  std::ifstream in(std::string(CB_HID_FIXTURE_DIR) + "/" + name, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline const std::vector<std::string>& wacomFixtures() {
  static const std::vector<std::string> kNames = {
      "wacom-pth460_v105.rdesc", "wacom-pth660_v145.rdesc", "wacom-pth660_v150.rdesc",
      "wacom-pth860_v145.rdesc", "wacom-pth860_v150.rdesc"};
  return kNames;
}

// The device files the product ships (config/devices in the source tree), loaded once; a
// mistake in them throws (and fails the test that asked).
inline const DeviceDatabase& shippedDevices() {
  static const std::shared_ptr<const DeviceDatabase> db = [] {
    DeviceFileLoad load = loadDeviceDirectory(std::string(CB_SOURCE_DIR) + "/config/devices");
    if (!load.errors.empty()) throw std::runtime_error(load.errors.front());
    return load.database;
  }();
  return *db;
}

inline const DeviceEntry& shippedEntry(uint16_t vendor, uint16_t product) {
  const DeviceEntry* e = shippedDevices().find(vendor, product);
  if (!e) throw std::runtime_error("no device file entry for this USB id");
  return *e;
}

}  // namespace cb::test
