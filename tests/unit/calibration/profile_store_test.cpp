#include "calibration/profile_store.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace cb {
namespace {

namespace fs = std::filesystem;

class ProfileStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ =
        fs::temp_directory_path() /
        ("cb_profile_store_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    config_ = (root_ / "config").string();
    state_ = (root_ / "state").string();
    fs::create_directories(config_);
    intuos_.usb_vendor = 0x056a;
    intuos_.usb_product = 0x00b9;
  }
  void TearDown() override { fs::remove_all(root_); }
  void write(const std::string& path, const std::string& text) {
    fs::create_directories(fs::path(path).parent_path());
    std::ofstream(path) << text;
  }
  CalibrationProfile kioskProfile(uint16_t product, uint64_t serial, double rotation) {
    CalibrationProfile p;
    p.device.usb_vendor = 0x056a;
    p.device.usb_product = product;
    p.device.tool_serial = serial;
    p.area.rotation_deg = rotation;
    return p;
  }

  fs::path root_;
  std::string config_, state_;
  PenDeviceInfo intuos_;
};

TEST_F(ProfileStoreTest, BuiltInDefaultsWhenNothingExists) {
  ProfileSelection s = selectProfile(intuos_, 0, config_, state_);
  EXPECT_EQ(s.source, "built-in defaults");
  EXPECT_TRUE(s.profile == CalibrationProfile{});
  EXPECT_TRUE(s.messages.empty());
}

TEST_F(ProfileStoreTest, SavedProfileRoundTripsAndWins) {
  write(config_ + "/calibration.toml", "[area]\nrotation_deg = 5\n");
  std::string err;
  const CalibrationProfile saved = kioskProfile(0x00b9, 0, 90.0);
  const std::string path = saveProfile(saved, state_, &err);
  ASSERT_FALSE(path.empty()) << err;
  EXPECT_EQ(path, state_ + "/profiles/056a-00b9.toml");
  ProfileSelection s = selectProfile(intuos_, 0, config_, state_);
  EXPECT_EQ(s.source, path);
  EXPECT_TRUE(s.profile == saved);
}

TEST_F(ProfileStoreTest, ToolSerialProfileIsPreferredForThatToolOnly) {
  std::string err;
  ASSERT_FALSE(saveProfile(kioskProfile(0x00b9, 0, 90.0), state_, &err).empty());
  ASSERT_FALSE(saveProfile(kioskProfile(0x00b9, 0xabc, 180.0), state_, &err).empty());
  EXPECT_EQ(selectProfile(intuos_, 0xabc, config_, state_).profile.area.rotation_deg, 180.0);
  EXPECT_EQ(selectProfile(intuos_, 0xdef, config_, state_).profile.area.rotation_deg, 90.0);
}

TEST_F(ProfileStoreTest, ProfileForAnotherDeviceIsNeverApplied) {
  // A profile for a different tablet sits at this tablet's path (copied by hand, say).
  const CalibrationProfile foreign = kioskProfile(0x0357, 0, 270.0);
  write(profilePath(state_, 0x056a, 0x00b9, 0), formatCalibrationProfile(foreign));
  write(config_ + "/calibration.toml", "[area]\nrotation_deg = 5\n");
  ProfileSelection s = selectProfile(intuos_, 0, config_, state_);
  EXPECT_EQ(s.profile.area.rotation_deg, 5.0);
  EXPECT_EQ(s.source, config_ + "/calibration.toml");
  ASSERT_EQ(s.messages.size(), 1u);
  EXPECT_NE(s.messages[0].find("not applied"), std::string::npos) << s.messages[0];
  EXPECT_NE(s.messages[0].find("056a:0357"), std::string::npos) << s.messages[0];
}

TEST_F(ProfileStoreTest, CorruptProfileReportedWithFileAndLineAndDefaultsUsed) {
  const std::string path = profilePath(state_, 0x056a, 0x00b9, 0);
  write(path, "[device]\nusb_vendor = 0x056a\nusb_product = 0x00b9\n[area\nrotation_deg = 90\n");
  ProfileSelection s = selectProfile(intuos_, 0, "", state_);
  EXPECT_EQ(s.source, "built-in defaults");
  EXPECT_TRUE(s.profile == CalibrationProfile{});
  std::string all;
  for (const auto& m : s.messages) all += m + "\n";
  EXPECT_NE(all.find(path + ":4:"), std::string::npos) << all;
  EXPECT_NE(all.find("corrupt profile skipped"), std::string::npos) << all;
}

TEST_F(ProfileStoreTest, SaveNeedsADevice) {
  std::string err;
  EXPECT_TRUE(saveProfile(CalibrationProfile{}, state_, &err).empty());
  EXPECT_NE(err.find("names no device"), std::string::npos);
}

}  // namespace
}  // namespace cb
