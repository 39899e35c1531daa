// `cloudbrush devices` as a user runs it, on this machine (no tablet attached in CI): it says
// which backends it tried and what each saw, and reports a broken device file by file, line and
// column without giving up on the rest.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "tests/support/command_run.h"

namespace cb {
namespace {

TEST(DevicesCommand, SaysWhatEachBackendSawAndNamesABrokenDeviceFile) {
  const std::filesystem::path config =
      std::filesystem::temp_directory_path() / ("cb-devices-cmd-" + std::to_string(getpid()));
  std::filesystem::create_directories(config / "devices");
  std::filesystem::copy(std::string(CB_SOURCE_DIR) + "/config/devices/wacom-tools.toml",
                        config / "devices");
  std::ofstream(config / "devices" / "broken.toml") << "[family]\nname = \"x\"\nvendor = -3\n";
  const test::CommandRun run = test::runCommand("CLOUDBRUSH_CONFIG_DIR=" + config.string() + " " +
                                                CB_CLOUDBRUSH_BIN + " devices 2>&1");
  std::filesystem::remove_all(config);
  EXPECT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("device files: 1 loaded from " + (config / "devices").string()),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("broken.toml:3:10: family.vendor: -3 is outside 0..65535"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("\ntried:\n"), std::string::npos) << run.out;
  for (const char* backend : {"  evdev   (", "  hidraw  (", "  libusb  ("})
    EXPECT_NE(run.out.find(backend), std::string::npos) << backend << "\n" << run.out;
  // Either it lists a pen with its ranges, or it says that none was found.
  const bool none = run.out.find("no pen tablet found") != std::string::npos;
  const bool listed = run.out.find("        x 0..") != std::string::npos;
  EXPECT_NE(none, listed) << run.out;
}

}  // namespace
}  // namespace cb
