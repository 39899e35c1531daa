#include "app/core/config_paths.h"

#include <cstdlib>
#include <filesystem>

namespace cb {

std::string defaultConfigDir() {
  if (const char* e = std::getenv("CLOUDBRUSH_CONFIG_DIR")) return e;
  std::filesystem::path src = std::filesystem::path(CB_SOURCE_DIR) / "config";
  if (std::filesystem::exists(src)) return src.string();
  return "/usr/share/cloudbrush/config";
}

std::string stateDir() {
  std::filesystem::path dir;
  if (const char* e = std::getenv("CLOUDBRUSH_STATE_DIR")) {
    dir = e;
  } else if (const char* x = std::getenv("XDG_STATE_HOME")) {
    dir = std::filesystem::path(x) / "cloudbrush";
  } else {
    const char* home = std::getenv("HOME");
    dir = std::filesystem::path(home ? home : "/tmp") / ".local/state/cloudbrush";
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  return dir.string();
}

std::string configFile(const std::string& name) {
  return (std::filesystem::path(defaultConfigDir()) / name).string();
}

std::string defaultHidFixtureDir() {
  std::filesystem::path src(CB_HID_FIXTURE_DIR);
  if (std::filesystem::exists(src)) return src.string();
  return "/usr/share/cloudbrush/fixtures/hid";
}

}  // namespace cb
