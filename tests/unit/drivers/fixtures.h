// Test data shared by the driver tests: the real Wacom descriptors in tests/fixtures/hid
// (CB_HID_FIXTURE_DIR, set by cb_add_test).
#pragma once

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

}  // namespace cb::test
