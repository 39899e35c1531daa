#include "calibration/profile_store.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace cb {
namespace {

std::string deviceStem(uint16_t vendor, uint16_t product) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04x-%04x", vendor, product);
  return buf;
}

}  // namespace

std::string profilePath(const std::string& state_dir, uint16_t usb_vendor, uint16_t usb_product,
                        uint64_t tool_serial) {
  std::string stem = deviceStem(usb_vendor, usb_product);
  if (tool_serial != 0) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "-%llx", static_cast<unsigned long long>(tool_serial));
    stem += buf;
  }
  return (std::filesystem::path(state_dir) / "profiles" / (stem + ".toml")).string();
}

ProfileSelection selectProfile(const PenDeviceInfo& device, uint64_t tool_serial,
                               const std::string& config_dir, const std::string& state_dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> candidates;
  if (!state_dir.empty()) {
    if (tool_serial != 0) {
      candidates.push_back(
          profilePath(state_dir, device.usb_vendor, device.usb_product, tool_serial));
    }
    candidates.push_back(profilePath(state_dir, device.usb_vendor, device.usb_product, 0));
  }
  if (!config_dir.empty()) {
    candidates.push_back(profilePath(config_dir, device.usb_vendor, device.usb_product, 0));
    candidates.push_back((fs::path(config_dir) / "calibration.toml").string());
  }

  ProfileSelection sel;
  for (const std::string& path : candidates) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) continue;
    ProfileParseResult r = readCalibrationProfile(path);
    for (const auto& w : r.warnings) sel.messages.push_back("warning: " + w);
    if (!r.profile) {
      for (const auto& e : r.errors) sel.messages.push_back("error: " + e);
      sel.messages.push_back(path + ": corrupt profile skipped");
      continue;
    }
    if (!r.profile->device.matches(device, tool_serial)) {
      char buf[48];
      std::snprintf(buf, sizeof buf, "%04x:%04x", device.usb_vendor, device.usb_product);
      sel.messages.push_back(path + ": profile is for " + r.profile->device.describe() +
                             ", not this pen (" + buf + "); not applied");
      continue;
    }
    sel.profile = *r.profile;
    sel.source = path;
    return sel;
  }
  sel.source = "built-in defaults";
  return sel;
}

std::string saveProfile(const CalibrationProfile& profile, const std::string& state_dir,
                        std::string* error) {
  namespace fs = std::filesystem;
  if (!profile.device.usb_vendor || !profile.device.usb_product) {
    if (error) *error = "save profile: the profile names no device (usb_vendor/usb_product)";
    return {};
  }
  const std::string path = profilePath(state_dir, *profile.device.usb_vendor,
                                       *profile.device.usb_product, profile.device.tool_serial);
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  if (ec) {
    if (error) *error = fs::path(path).parent_path().string() + ": " + ec.message();
    return {};
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << formatCalibrationProfile(profile);
    out.flush();
    if (!out) {
      if (error) *error = tmp + ": write failed";
      return {};
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    if (error) *error = path + ": " + ec.message();
    return {};
  }
  return path;
}

}  // namespace cb
