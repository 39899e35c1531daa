#include "app/core/config_paths.h"
#include "app/core/config_override.h"

#include <cstdlib>
#include <filesystem>

namespace cb {
namespace {

// Paths compiled in from the build machine are read only by a binary run from its build tree
// (tests, a developer): an installed binary never looks there, so a local user who creates that
// path on a kiosk cannot set its settings.
bool runningFromBuildTree() {
  std::error_code ec;
  const std::string exe = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  return !ec && exe.rfind(std::string(CB_BUILD_DIR) + "/", 0) == 0;
}

}  // namespace

std::string defaultConfigDir() {
  if (const char* e = std::getenv("CLOUDBRUSH_CONFIG_DIR")) return e;
  std::filesystem::path src = std::filesystem::path(CB_SOURCE_DIR) / "config";
  std::error_code ec;
  if (runningFromBuildTree() && std::filesystem::exists(src, ec)) return src.string();
  return "/usr/share/cloudbrush/config";
}

std::string configOverrideFile(const std::string& name) {
  std::string dir;
  if (const char* e = std::getenv("CLOUDBRUSH_CONFIG_OVERRIDE_DIR"))
    dir = e;
  else if (!runningFromBuildTree())
    dir = "/etc/cloudbrush";
  if (dir.empty()) return "";
  const std::filesystem::path path = std::filesystem::path(dir) / name;
  std::error_code ec;
  return std::filesystem::exists(path, ec) ? path.string() : "";
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
  std::error_code ec;
  if (runningFromBuildTree() && std::filesystem::exists(src, ec)) return src.string();
  return "/usr/share/cloudbrush/fixtures/hid";
}

}  // namespace cb
