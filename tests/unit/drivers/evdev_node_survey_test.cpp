#include "drivers/evdev/evdev_node_survey.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace cb {
namespace {

TEST(EvdevNodeSurvey, NamesADirectoryItCannotList) {
  EvdevSurvey s = surveyEvdevNodes("/nonexistent/cloudbrush-input");
  EXPECT_EQ(s.dir, "/nonexistent/cloudbrush-input");
  EXPECT_NE(s.dir_error.find("No such file"), std::string::npos) << s.dir_error;
  EXPECT_TRUE(s.nodes.empty());
}

TEST(EvdevNodeSurvey, ReportsEveryEventNodeInOrderWithWhyItIsNoPen) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cb-evdev-survey-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const char* name : {"event10", "event2", "mouse0"}) std::ofstream(dir / name) << "x";
  EvdevSurvey s = surveyEvdevNodes(dir.string());
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(s.dir_error.empty()) << s.dir_error;
  ASSERT_EQ(s.nodes.size(), 2u) << "only event* nodes";
  EXPECT_EQ(std::filesystem::path(s.nodes[0].path).filename(), "event2");
  EXPECT_EQ(std::filesystem::path(s.nodes[1].path).filename(), "event10");
  for (const EvdevNodeReport& n : s.nodes) {
    EXPECT_EQ(n.kind, EvdevNodeKind::kCannotOpen);
    EXPECT_NE(n.detail.find("not an input device"), std::string::npos) << n.detail;
    EXPECT_FALSE(n.permission_denied);
  }
}

}  // namespace
}  // namespace cb
