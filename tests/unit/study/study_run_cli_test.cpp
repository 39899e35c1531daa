// `cloudbrush study run` (the real binary): a protocol with an error is refused with
// FILE:LINE: FIELD before any display opens or any session folder is made; options the protocol
// needs are asked for by name; a surfaceless run makes the session folder with session.json,
// the journal and the answer files at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "app/session/synthetic_session.h"
#include "app/shell/study/study_page.h"
#include "app/study/protocol.h"
#include "drivers/core/journal.h"
#include "tests/support/command_run.h"
#include "tests/support/file_text.h"

namespace cb {
namespace {

using cb::test::readText;

std::string tempDir(const std::string& name) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / (name + std::to_string(::getpid()))).string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(StudyRunCli, AProtocolWithAnErrorIsRefusedBeforeAnyScreen) {
  const std::string dir = tempDir("cb_study_run_cli_");
  // The bundled protocol with one typo'd value: the task's minutes are text.
  std::string text = readText(std::string(CB_SOURCE_DIR) + "/config/study/thesis_2014.toml");
  const std::string from = "[[task]]\nid = \"cloud2\"";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + from.size(), "\nminutes = \"ten\"");
  int line = 1;
  for (size_t i = 0; i < at + from.size() + 1; ++i) line += text[i] == '\n';
  const std::string protocol = dir + "/broken.toml";
  std::ofstream(protocol) << text;
  // Its pictures next to it, so only the error stops it.
  std::filesystem::copy(std::string(CB_SOURCE_DIR) + "/config/study/images", dir + "/images");
  const test::CommandRun run = test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " study run " +
                                                protocol + " --data-dir " + dir +
                                                "/data --operator XY --venue uct-lab "
                                                "--display surfaceless --backend none --frames 3");
  EXPECT_EQ(run.status, 1) << run.out;
  EXPECT_NE(run.out.find(protocol + ":" + std::to_string(line) + ": task[2].minutes"),
            std::string::npos)
      << run.out;
  EXPECT_EQ(run.out.find("session folder"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("display"), std::string::npos) << "no display was opened: " << run.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/data")) << "no session folder on a bad protocol";
  std::filesystem::remove_all(dir);
}

TEST(StudyRunCli, TheBundledProtocolAsksForItsOperatorAndVenueThenRecords) {
  const std::string dir = tempDir("cb_study_run_cli_ok_");
  const std::string base = std::string(CB_CLOUDBRUSH_BIN) + " study run --data-dir " + dir +
                           "/data --display surfaceless --backend none --frames 4";
  test::CommandRun run = test::runCommand(base + " --venue uct-lab");
  EXPECT_EQ(run.status, 2) << run.out;
  EXPECT_NE(run.out.find("--operator INITIALS"), std::string::npos) << run.out;
  run = test::runCommand(base + " --operator XY --venue moon");
  EXPECT_EQ(run.status, 2) << run.out;
  EXPECT_NE(run.out.find("uct-lab, cityvarsity"), std::string::npos) << run.out;

  run = test::runCommand(base + " --operator XY --venue cityvarsity");
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("participant: P01 (number 1)"), std::string::npos) << run.out;
  std::string folder;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/data"))
    folder = entry.path().string();
  ASSERT_EQ(std::filesystem::path(folder).filename().string().rfind("P01-", 0), 0u) << folder;
  const std::string json = readText(folder + "/session.json");
  EXPECT_NE(json.find("\"venue\": \"cityvarsity\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"operator\": \"XY\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"status\": \"running\""), std::string::npos) << "stopped at consent";
  EXPECT_NE(json.find("\"platform\": \"surfaceless\""), std::string::npos) << json;
  // An offscreen buffer has no refresh rate: null, and why (not a made-up number).
  EXPECT_NE(json.find("\"refresh_hz\": null, \"refresh_note\": \"surfaceless: "), std::string::npos)
      << json;
  EXPECT_NE(readText(folder + "/questionnaire.csv").find("P01,NA,NA"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(folder + "/session.cbj"));
  // The next run is participant 2 (the next free id), with that participant's task order.
  run = test::runCommand(base + " --operator XY --venue cityvarsity");
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("participant: P02 (number 2)"), std::string::npos) << run.out;
  std::filesystem::remove_all(dir);
}

TEST(StudyRunCli, AParticipantWithASessionFolderAlreadyIsRefusedAndZeroIsNoNumber) {
  const std::string dir = tempDir("cb_study_run_cli_dup_");
  const std::string base = std::string(CB_CLOUDBRUSH_BIN) + " study run --data-dir " + dir +
                           "/data --display surfaceless --backend none --frames 2 --operator XY "
                           "--venue uct-lab";
  test::CommandRun run = test::runCommand(base + " --participant 2");
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("participant: P02 (number 2)"), std::string::npos) << run.out;
  std::vector<std::string> folders;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/data"))
    folders.push_back(entry.path().string());
  ASSERT_EQ(folders.size(), 1u);

  // Participant 2 again: refused before any folder or display, naming the folder and --resume.
  run = test::runCommand(base + " --participant 2");
  EXPECT_EQ(run.status, 2) << run.out;
  EXPECT_NE(run.out.find("P02 has a session folder already: " + folders[0]), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("--resume " + folders[0]), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("the next free number is 1"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("session folder:"), std::string::npos) << run.out;
  const auto entries = std::filesystem::directory_iterator(dir + "/data");
  EXPECT_EQ(std::distance(begin(entries), end(entries)), 1) << "no second folder of P02";

  // 0 is not a participant number (P01 is 1); leaving the option out takes the next free one.
  run = test::runCommand(base + " --participant 0");
  EXPECT_EQ(run.status, 2) << run.out;
  EXPECT_NE(run.out.find("--participant 0: expected N >= 1"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("leave --participant out"), std::string::npos) << run.out;
  run = test::runCommand(base);
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("participant: P01 (number 1)"), std::string::npos) << run.out;
  std::filesystem::remove_all(dir);
}

// A recorded pen (a Device record and samples) that taps the middle of `target` at `t_ns`, on
// the synthetic tablet mapped onto a `w` × `h` screen.
void recordTap(const StudyTarget* target, int w, int h, int64_t t_ns, const std::string& path) {
  ASSERT_TRUE(target);
  const PenDeviceInfo tablet = syntheticTablet(w, h);
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path)) << journal.error();
  const std::vector<uint8_t> device = encodeDeviceInfo(tablet);
  ASSERT_TRUE(journal.append(JournalRecordType::kDevice, t_ns, device.data(), device.size()));
  const float x = 0.5f * (target->x0 + target->x1), y = 0.5f * (target->y0 + target->y1);
  for (int i = 0; i < 10; ++i) {
    const bool tip = i >= 3 && i < 7, proximity = i < 9;
    PenSample s;
    s.t_ns = t_ns + (i + 1) * 5'000'000;
    s.x_mm = double(x) * double(tablet.x_max) / tablet.x_res / w;
    s.y_mm = double(y) * double(tablet.y_max) / tablet.y_res / h;
    s.x_raw = int32_t(std::lround(s.x_mm * tablet.x_res));
    s.y_raw = int32_t(std::lround(s.y_mm * tablet.y_res));
    s.pressure_raw = tip ? tablet.pressure_max / 2 : 0;
    s.pressure = tip ? 0.5f : 0.0f;
    s.buttons = tip ? kPenTip : 0u;
    s.tool = proximity ? PenTool::kPen : PenTool::kNone;
    s.in_proximity = proximity;
    ASSERT_TRUE(journal.appendPenSample(s));
  }
}

TEST(StudyRunCli, DecliningConsentEndsTheRunWithExitZeroAndNoTaskData) {
  const std::string dir = tempDir("cb_study_run_cli_decline_");
  const int w = 1920, h = 1080;
  const StudyProtocol protocol = loadStudyProtocol(defaultStudyProtocolPath());
  const StudyRunState consent(protocol, 1, 0);
  StudyPageInput input;  // measured with the runner's font
  std::string font_error;
  input.measure = studyPageFont(protocol, &font_error);
  ASSERT_TRUE(input.measure) << font_error;
  const StudyPage page = buildStudyPage(consent, input, w, h);
  const std::string pen = dir + "/pen.cbj";
  ASSERT_NO_FATAL_FAILURE(
      recordTap(page.find(StudyTargetAction::kDecline), w, h, 5'000'000'000, pen));
  const test::CommandRun run = test::runCommand(
      std::string(CB_CLOUDBRUSH_BIN) + " study run --data-dir " + dir +
      "/data --display surfaceless --size 1920x1080 --grid 64 --backend replay --journal " + pen +
      " --operator XY --venue uct-lab --end-seconds 0.3 --seconds 30");
  ASSERT_EQ(run.status, 0) << run.out;
  EXPECT_NE(run.out.find("consent declined after"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("P01 declined consent; the session ended before any task"),
            std::string::npos)
      << run.out;
  std::string folder;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/data"))
    folder = entry.path().string();
  const std::string json = readText(folder + "/session.json");
  EXPECT_NE(json.find("\"status\": \"declined\""), std::string::npos) << json;
  EXPECT_FALSE(std::filesystem::exists(folder + "/tasks"));
  // The folder holds the session's record and journal, no answer file with a row of NAs.
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    files.push_back(entry.path().filename().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"session.cbj", "session.json"}));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
