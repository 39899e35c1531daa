// `cloudbrush study export --bids DIR` of two short study sessions recorded by the real runner
// (tests/support/short_study.h, participants 1 and 2, `study run --backend replay`): the
// dataset holds what the study's own exports hold (beh.tsv is trials.csv, the motion recording
// is samples.csv's samples, the events' task rows are the trials), every TSV column is
// described in its JSON sidecar, and the BIDS validator (npm's bids-validator, run by
// bids_validate.sh) reports no error. Its warnings are printed.
//
// CB_KEEP_BIDS=DIR keeps the sessions and the dataset there for looking.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "app/study/protocol.h"
#include "tests/support/command_run.h"
#include "tests/support/file_text.h"
#include "tests/support/short_study.h"

namespace cb {
namespace {

namespace fs = std::filesystem;
using Table = std::vector<std::vector<std::string>>;

using cb::test::readText;

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == sep)
      out.emplace_back();
    else
      out.back().push_back(c);
  }
  return out;
}

// Rows of a TSV or of a CSV without quoted fields (the rows compared here have none).
Table readTable(const std::string& path, char sep) {
  Table rows;
  std::istringstream in(readText(path));
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) rows.push_back(split(line, sep));
  return rows;
}

// The rows of a study CSV export whose session column is `session`, without those columns.
Table rowsOfSession(const Table& csv, const std::string& session) {
  Table out;
  for (size_t i = 1; i < csv.size(); ++i)
    if (csv[i].size() > 1 && csv[i][1] == session) out.push_back(csv[i]);
  return out;
}

size_t column(const Table& t, const std::string& name) {
  for (size_t i = 0; i < t[0].size(); ++i)
    if (t[0][i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

// Every column of the TSV's header is a key of its sidecar.
void expectDescribed(const std::string& tsv, const std::string& json) {
  const std::string sidecar = readText(json);
  ASSERT_FALSE(sidecar.empty()) << json;
  const Table table = readTable(tsv, '\t');
  ASSERT_FALSE(table.empty()) << tsv;
  for (const std::string& name : table[0])
    EXPECT_NE(sidecar.find("\"" + name + "\": {\"Description\""), std::string::npos)
        << name << " of " << tsv << " is not described in " << json;
}

// What the test exports: two participants' sessions of the short study (participant 1 with a
// cloud saved by the painter's Save), as CSV (`csv`) and as a BIDS dataset (`bids`).
struct Exported {
  std::string dir, bids, csv;
  StudyProtocol protocol;
  std::vector<std::string> journals, ids;
  std::string saved_name, saved_bytes;
  test::CommandRun exported;
};

// Runs both sessions with the recorded pen in `e->dir`, adds the saved cloud, exports.
void runTwoSessionsAndExport(Exported* e) {
  const std::string& dir = e->dir;
  e->bids = dir + "/bids", e->csv = dir + "/csv";
  fs::copy(std::string(CB_SOURCE_DIR) + "/config/study/images", dir + "/images");
  const std::string protocol_path = dir + "/short.toml";
  std::ofstream(protocol_path) << test::kShortStudyProtocol;
  e->protocol = loadStudyProtocol(protocol_path);
  const std::string pen = dir + "/pen.cbj";
  ASSERT_NO_FATAL_FAILURE(test::recordShortStudyPen(e->protocol, pen));
  for (int participant : {1, 2}) {
    const test::CommandRun run = test::runCommand(
        std::string(CB_CLOUDBRUSH_BIN) + " study run " + protocol_path +
        " --display surfaceless --size " + std::to_string(test::kShortStudyWidth) + "x" +
        std::to_string(test::kShortStudyHeight) + " --grid 32 --participant " +
        std::to_string(participant) + " --backend replay --journal " + pen +
        " --end-seconds 0.3 --seconds 90 --data-dir " + dir + "/data");
    ASSERT_EQ(run.status, 0) << run.out;
    const size_t at = run.out.find("session folder: ");
    ASSERT_NE(at, std::string::npos) << run.out;
    const std::string folder = run.out.substr(at + 16, run.out.find('\n', at) - at - 16);
    ASSERT_TRUE(fs::exists(folder + "/session.cbj")) << run.out;
    e->journals.push_back(folder + "/session.cbj");
    e->ids.push_back(fs::path(folder).filename().string());
  }
  // A cloud participant 1 saved with the painter's Save (the session folder's saved/).
  e->saved_name = "cloud-2026-11-29_10-00-00.vol";
  e->saved_bytes = std::string("CBVOL\0\x01 a saved cloud's bytes\xff", 30);
  fs::create_directories(fs::path(e->journals[0]).parent_path() / "saved");
  std::ofstream((fs::path(e->journals[0]).parent_path() / "saved" / e->saved_name).string(),
                std::ios::binary)
      << e->saved_bytes;
  e->exported =
      test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " study export " + e->journals[0] + " " +
                       e->journals[1] + " --out " + e->csv + " --bids " + e->bids);
  ASSERT_EQ(e->exported.status, 0) << e->exported.out;
}

// The saved cloud in sourcedata/ and in --out; the dataset's top-level files; participants.tsv.
void checkSavedCloudAndParticipants(const Exported& e) {
  const std::string &bids = e.bids, &csv = e.csv, &saved_name = e.saved_name,
                    &saved_bytes = e.saved_bytes;
  const std::vector<std::string>& ids = e.ids;
  const test::CommandRun& exported = e.exported;
  // The saved cloud, byte for byte, in sourcedata/ (BIDS's place for files in their own
  // formats); participant 2 saved none.
  EXPECT_EQ(readText(bids + "/sourcedata/sub-C01/ses-1/saved/" + saved_name), saved_bytes);
  EXPECT_FALSE(fs::exists(bids + "/sourcedata/sub-C02"));
  // --out carries the same copy (one code path, app/study/saved_clouds.h), under the session id.
  EXPECT_EQ(readText(csv + "/saved/" + ids[0] + "/" + saved_name), saved_bytes);
  EXPECT_FALSE(fs::exists(csv + "/saved/" + ids[1]));
  EXPECT_NE(exported.out.find(csv + "/saved/" + ids[0] + "/" + saved_name), std::string::npos)
      << "the copy is named among the files written\n"
      << exported.out;
  for (const char* file : {"dataset_description.json", "README", "participants.json"})
    EXPECT_TRUE(fs::exists(bids + "/" + file)) << file;
  const Table participants = readTable(bids + "/participants.tsv", '\t');
  ASSERT_EQ(participants.size(), 3u) << "a header and one row per participant";
  EXPECT_EQ(participants[1][0], "sub-C01");
  EXPECT_EQ(participants[2][0], "sub-C02");
  expectDescribed(bids + "/participants.tsv", bids + "/participants.json");
}

// phenotype/: the Likert answers (the short study's pen answers 4, 2, 5), a row per session,
// every item described with its statement and the scale's levels; no free-text questions.
void checkPhenotype(const Exported& e) {
  const std::string& bids = e.bids;
  const StudyProtocol& protocol = e.protocol;
  const Table questionnaire = readTable(bids + "/phenotype/questionnaire.tsv", '\t');
  const std::vector<std::vector<std::string>> expected_answers = {
      {"participant_id", "session_id", "Q1", "Q2", "Q3"},
      {"sub-C01", "ses-1", "4", "2", "5"},
      {"sub-C02", "ses-1", "4", "2", "5"}};
  EXPECT_EQ(questionnaire, expected_answers);
  const std::string questionnaire_json = readText(bids + "/phenotype/questionnaire.json");
  EXPECT_NE(questionnaire_json.find("\"MeasurementToolMetadata\": {\"Description\""),
            std::string::npos)
      << questionnaire_json;
  for (const QuestionnaireItem& item : protocol.items)
    EXPECT_NE(questionnaire_json.find("\"" + item.id + "\": {\"Description\": \"" + item.text +
                                      "\", \"Levels\": {\"1\": \"strongly disagree\""),
              std::string::npos)
        << item.id << " in " << questionnaire_json;
  EXPECT_FALSE(fs::exists(bids + "/phenotype/feedback.tsv")) << "the protocol has no free text";
}

// The participant's sessions.tsv, described.
void checkSessionsTable(const std::string& bids, const std::string& subject, const std::string& ses,
                        const std::string& id) {
  const std::string sessions = bids + "/" + subject + "/" + subject + "_sessions";
  const Table session_rows = readTable(sessions + ".tsv", '\t');
  ASSERT_EQ(session_rows.size(), 2u);
  EXPECT_EQ(session_rows[1][0], "ses-" + ses);
  EXPECT_EQ(session_rows[1][2], id);
  expectDescribed(sessions + ".tsv", sessions + ".json");
}

// beh.tsv is the session's rows of trials.csv (missing values n/a instead of NA).
void checkBeh(const std::string& base, const std::string& name, const Table& trials,
              const std::string& id, Table* beh_out) {
  const Table beh = readTable(base + "beh/" + name + "_beh.tsv", '\t');
  const Table session_trials = rowsOfSession(trials, id);
  ASSERT_EQ(session_trials.size(), 2u) << "the short study's two tasks";
  ASSERT_EQ(beh.size(), session_trials.size() + 1);
  for (size_t r = 0; r < session_trials.size(); ++r) {
    std::vector<std::string> expected = session_trials[r];
    for (std::string& v : expected)
      if (v == "NA") v = "n/a";
    EXPECT_EQ(beh[r + 1], expected) << "trial " << r;
  }
  expectDescribed(base + "beh/" + name + "_beh.tsv", base + "beh/" + name + "_beh.json");
  *beh_out = beh;
}

// events.tsv: the stages in order; each task row is its trial (onset, order, figures).
void checkEvents(const std::string& base, const std::string& name, const Table& beh) {
  const Table events = readTable(base + "beh/" + name + "_events.tsv", '\t');
  expectDescribed(base + "beh/" + name + "_events.tsv", base + "beh/" + name + "_events.json");
  ASSERT_GT(events.size(), 1u);
  EXPECT_EQ(events[0][0], "onset");
  EXPECT_EQ(events[0][1], "duration");
  EXPECT_EQ(events[0][2], "trial_type");
  std::vector<std::string> stages;
  size_t task = 0;
  for (size_t r = 1; r < events.size(); ++r) {
    stages.push_back(events[r][2]);
    if (r > 1) {
      EXPECT_LE(std::stod(events[r - 1][0]), std::stod(events[r][0])) << "sorted";
    }
    if (events[r][2] != "task" || task >= beh.size() - 1) continue;
    const std::vector<std::string>& t = beh[++task];
    EXPECT_EQ(events[r][0], t[column(beh, "onset_s")]);
    EXPECT_EQ(events[r][3], t[column(beh, "task")]);
    EXPECT_EQ(events[r][column(events, "active_duration")], t[column(beh, "duration_s")]);
    EXPECT_GE(std::stod(events[r][1]) + 1e-9, std::stod(t[column(beh, "duration_s")]))
        << "the recording's span holds the stage clock's";
  }
  EXPECT_EQ(task, 2u);
  const std::vector<std::string> order = {"consent",  "participant",  "introduction",
                                          "tutorial", "free-drawing", "task",
                                          "task",     "questionnaire"};
  EXPECT_EQ(stages, order);
  EXPECT_EQ(readText(base + "motion/" + name + "_events.tsv"),
            readText(base + "beh/" + name + "_events.tsv"));
}

// The motion recording: samples.csv's samples of the session, a column per channel.
void checkMotion(const std::string& base, const std::string& name, const Table& samples,
                 const std::string& id) {
  const Table channels = readTable(base + "motion/" + name + "_tracksys-tablet_channels.tsv", '\t');
  const Table motion = readTable(base + "motion/" + name + "_tracksys-tablet_motion.tsv", '\t');
  const Table session_samples = rowsOfSession(samples, id);
  ASSERT_EQ(motion.size(), session_samples.size());
  ASSERT_GT(motion.size(), 10u);
  EXPECT_EQ(channels[0][0], "name");
  EXPECT_EQ(channels[0][1], "component");
  const size_t t_s = column(samples, "t_s"), x = column(samples, "x_mm"),
               y = column(samples, "y_mm"), p = column(samples, "pressure");
  for (size_t r = 0; r < motion.size(); ++r) {
    ASSERT_EQ(motion[r].size(), channels.size() - 1) << "row " << r;
    EXPECT_EQ(motion[r][0], session_samples[r][t_s]) << "latency, row " << r;
    EXPECT_EQ(motion[r][1], session_samples[r][x]) << "pen_x, row " << r;
    EXPECT_EQ(motion[r][2], session_samples[r][y]) << "pen_y, row " << r;
    EXPECT_EQ(motion[r][5], session_samples[r][p]) << "pressure, row " << r;
  }
  const std::string motion_json =
      readText(base + "motion/" + name + "_tracksys-tablet_motion.json");
  EXPECT_NE(motion_json.find("\"SamplingFrequency\": "), std::string::npos) << motion_json;
  EXPECT_NE(motion_json.find("\"LATENCYChannelCount\": 1"), std::string::npos) << motion_json;
}

TEST(StudyBidsExport, TheDatasetHoldsTheStudysExportsAndTheValidatorFindsNoError) {
  const char* keep = std::getenv("CB_KEEP_BIDS");
  Exported e;
  e.dir = keep ? std::string(keep)
               : (fs::temp_directory_path() / ("cb_bids_" + std::to_string(::getpid()))).string();
  const std::string& dir = e.dir;
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_NO_FATAL_FAILURE(runTwoSessionsAndExport(&e));
  const std::string &bids = e.bids, &csv = e.csv;
  ASSERT_NO_FATAL_FAILURE(checkSavedCloudAndParticipants(e));
  ASSERT_NO_FATAL_FAILURE(checkPhenotype(e));

  const Table trials = readTable(csv + "/trials.csv", ','),
              samples = readTable(csv + "/samples.csv", ',');
  for (size_t i = 0; i < e.ids.size(); ++i) {
    SCOPED_TRACE(e.ids[i]);
    const std::string subject = "sub-C0" + std::to_string(i + 1);
    const std::string ses = "1";  // each participant's first session
    ASSERT_NO_FATAL_FAILURE(checkSessionsTable(bids, subject, ses, e.ids[i]));
    const std::string base = bids + "/" + subject + "/ses-" + ses + "/";
    const std::string name = subject + "_ses-" + ses + "_task-cloudpainting";
    Table beh;
    ASSERT_NO_FATAL_FAILURE(checkBeh(base, name, trials, e.ids[i], &beh));
    ASSERT_NO_FATAL_FAILURE(checkEvents(base, name, beh));
    ASSERT_NO_FATAL_FAILURE(checkMotion(base, name, samples, e.ids[i]));
  }

  // The validator: no error (its warnings are printed).
  const test::CommandRun validator =
      test::runCommand(std::string(CB_BIDS_VALIDATE) + " " + bids + " " + CB_BIDS_VALIDATOR_PREFIX);
  std::printf("%s", validator.out.c_str());
  EXPECT_EQ(validator.status, 0) << validator.out;
  EXPECT_NE(validator.out.find(": 0 errors,"), std::string::npos) << validator.out;
  if (!keep) fs::remove_all(dir);
}

}  // namespace
}  // namespace cb
