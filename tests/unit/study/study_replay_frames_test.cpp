// `cloudbrush replay SESSION --frames DIR` of a recorded study session ("re-runs the
// journal through the same input router and screens ... --frames DIR writes one image per
// frame"). The short study of tests/support/short_study.h is run once by the real runner
// (`study run --backend replay`, its clock the pen's time line), then its session.cbj is replayed
// with --frames on EGL surfaceless. The frames are the runner's own screens at their times: the
// consent page before the first tap, the first task (the sky, its reference picture in the
// panel) while its stroke is painted, the questionnaire before the first answer, the closing
// page at the end; the task-end volumes equal the ones the runner saved, byte for byte.
//
// CB_KEEP_FRAMES=DIR keeps the frames there for looking.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "app/render/image_io.h"
#include "app/shell/study/study_page.h"
#include "app/study/protocol.h"
#include "app/study/reference_picture.h"
#include "app/study/study_run_state.h"
#include "drivers/core/journal.h"

#include "tests/support/command_run.h"
#include "tests/support/short_study.h"

namespace cb {
namespace {

constexpr int kW = test::kShortStudyWidth, kH = test::kShortStudyHeight;
constexpr int64_t kSecond = 1'000'000'000;
constexpr double kFps = 5.0;

std::string capture(const std::string& text, const std::string& pattern) {
  std::smatch match;
  return std::regex_search(text, match, std::regex(pattern)) ? match[1].str() : std::string();
}

// The form pages' dark slate background (and its text) against the painter's lit sky.
bool dark(const uint8_t* p) {
  return std::max({p[0], p[1], p[2]}) < 60;
}

// The share of dark pixels where a painting stage shows the sky (left of the runner's panel,
// between the status lines): high on a form page, low over the sky.
double darkShare(const ImageRgba8& frame) {
  long n = 0, all = 0;
  for (int y = frame.height / 5; y < frame.height * 4 / 5; ++y)
    for (int x = 0; x < frame.width * 3 / 5; ++x, ++all) n += dark(frame.at(x, y));
  return double(n) / double(all);
}

// Mean RGB of the frame inside a target's box, inset by a quarter of its size.
glm::vec3 meanIn(const ImageRgba8& frame, float x0, float y0, float x1, float y1) {
  const float ix = 0.25f * (x1 - x0), iy = 0.25f * (y1 - y0);
  glm::vec3 sum(0.0f);
  long n = 0;
  for (int y = int(y0 + iy); y < int(y1 - iy); ++y)
    for (int x = int(x0 + ix); x < int(x1 - ix); ++x, ++n)
      sum += glm::vec3(frame.at(x, y)[0], frame.at(x, y)[1], frame.at(x, y)[2]);
  return n ? sum / float(n) : sum;
}

glm::vec3 meanOf(const ImageRgba8& image) {
  return meanIn(image, 0, 0, float(image.width), float(image.height));
}

bool boxShown(const ImageRgba8& frame, const StudyTarget* target) {
  if (!target) return false;
  const glm::vec3 m = meanIn(frame, target->x0, target->y0, target->x1, target->y1);
  return std::max({m.r, m.g, m.b}) > 90.0f;  // a target's box (the page around it is < 60)
}

// The short study run to its end by the recorded pen in `dir`, and the session's checksum.
struct Recorded {
  StudyProtocol protocol;
  std::string folder, session_volume;
};

void runSession(const std::string& dir, Recorded* r) {
  std::filesystem::create_directories(dir);
  std::filesystem::copy(std::string(CB_SOURCE_DIR) + "/config/study/images", dir + "/images");
  const std::string protocol_path = dir + "/short.toml";
  std::ofstream(protocol_path) << test::kShortStudyProtocol;
  r->protocol = loadStudyProtocol(protocol_path);
  const std::string pen = dir + "/pen.cbj";
  ASSERT_NO_FATAL_FAILURE(test::recordShortStudyPen(r->protocol, pen));

  r->folder = dir + "/data/C01";
  const test::CommandRun run = test::runCommand(
      std::string(CB_CLOUDBRUSH_BIN) + " study run " + protocol_path +
      " --display surfaceless --size " + std::to_string(kW) + "x" + std::to_string(kH) +
      " --grid 64 --participant 1 --backend replay --journal " + pen +
      " --end-seconds 0.3 --seconds 90 --resume " + r->folder);
  ASSERT_EQ(run.status, 0) << run.out;
  ASSERT_NE(run.out.find("stage done"), std::string::npos) << run.out;
  r->session_volume = capture(run.out, "volume checksum ([0-9a-f]{16})");
}

// `cloudbrush replay` of the session into `frames`: the task volumes and the session's are the
// runner's.
void replayFrames(const Recorded& r, const std::string& frames, test::CommandRun* replay) {
  const std::string& folder = r.folder;
  const std::string& session_volume = r.session_volume;
  *replay =
      test::runCommand(std::string(CB_CLOUDBRUSH_BIN) + " replay " + folder +
                       "/session.cbj --fps " + std::to_string(int(kFps)) + " --frames " + frames);
  ASSERT_EQ(replay->status, 0) << replay->out;
  // The volumes: each task's end as the runner saved it, and the whole session.
  for (const char* task : {"first", "second"})
    EXPECT_NE(replay->out.find(std::string("task ") + task + ": volume checksum "),
              std::string::npos)
        << replay->out;
  EXPECT_EQ(std::regex_search(replay->out, std::regex("task (first|second): volume checksum "
                                                      "[0-9a-f]{16}, identical to ")),
            true)
      << replay->out;
  EXPECT_EQ(replay->out.find("DIFFERENT"), std::string::npos) << replay->out;
  EXPECT_EQ(capture(replay->out, "volume checksum: ([0-9a-f]{16})"), session_volume) << replay->out;
  EXPECT_TRUE(std::regex_search(replay->out, std::regex("frames [0-9]+/[0-9]+ \\(100%\\)")))
      << "progress on stderr\n"
      << replay->out;
}

// The frames' time line: the journal's first pen sample or study marker, the frame count.
struct Timeline {
  std::string frames;
  int64_t t_first = 0;
  long total = 0;

  // The frame shown at `seconds` after the pen journal's start (short_study.h's times).
  ImageRgba8 frameAt(double seconds) const {
    const int64_t t = test::kShortStudyT0 + int64_t(seconds * 1e9);
    const long k = std::clamp(long(std::ceil(double(t - t_first) * 1e-9 * kFps)), 0L, total - 1);
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06ld.png", k);
    return readPng(frames + name);
  }
};

// The time line: the journal's first to last pen sample or study marker; a PNG a frame.
void checkTimeline(const std::string& folder, const std::string& replay_out, Timeline* t) {
  const JournalReadResult journal = readJournal(folder + "/session.cbj");
  int64_t t_last = 0;
  t->t_first = INT64_MAX;
  for (const JournalRecord& r : journal.records) {
    const bool marker = r.type == JournalRecordType::kMarker && r.text().rfind("study.", 0) == 0 &&
                        r.text().rfind("study.info ", 0) != 0;
    if (r.type != JournalRecordType::kPenSample && !marker) continue;
    t->t_first = std::min(t->t_first, r.t_ns);
    t_last = std::max(t_last, r.t_ns);
  }
  t->total = long(std::floor(double(t_last - t->t_first) * 1e-9 * kFps)) + 1;
  EXPECT_EQ(capture(replay_out, "frames: ([0-9]+) PNGs"), std::to_string(t->total)) << replay_out;
  long files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(t->frames))
    files += entry.path().extension() == ".png";
  EXPECT_EQ(files, t->total);
}

// The pages as the runner lays them out at each stage; the task's picture as shown.
struct Pages {
  StudyPage consent, task, questionnaire;
  ImageRgba8 picture;
};

void layOutPages(const StudyProtocol& protocol, const std::string& dir, Pages* p) {
  StudyRunState layout(protocol, 1, 0);
  StudyPageInput form_input;  // measured with the runner's font
  std::string font_error;
  form_input.measure = studyPageFont(protocol, &font_error);
  ASSERT_TRUE(form_input.measure) << font_error;
  p->consent = buildStudyPage(layout, form_input, kW, kH);
  layout.agree(0);
  layout.proceed(0);
  layout.proceed(0);
  layout.completeTutorialStep(0);
  layout.closeStage(0);
  layout.tick(7 * kSecond);
  layout.closeStage(7 * kSecond);  // free drawing: the first task now
  ASSERT_EQ(layout.stage(), StudyStageKind::kTask);
  // As the participant sees it: composited over the paper background (reference_picture.h).
  p->picture = referencePictureForDisplay(readPng(dir + "/images/cloud1_duck.png"));
  StudyPageInput task_input = form_input;
  task_input.image_aspect = float(p->picture.width) / float(p->picture.height);
  p->task = buildStudyPage(layout, task_input, kW, kH);
  for (int i = 2; i < 4; ++i) {
    layout.tick(7 * kSecond * i);
    layout.closeStage(7 * kSecond * i);
  }
  ASSERT_EQ(layout.stage(), StudyStageKind::kQuestionnaire);
  p->questionnaire = buildStudyPage(layout, form_input, kW, kH);
}

// What the frames show at consent, in the first task and at the questionnaire.
void checkFramesShowThePages(const Timeline& t, const Pages& p) {
  // Consent, before the first tap (1.0 s): a form on black, its "I agree" box drawn.
  const ImageRgba8 at_consent = t.frameAt(0.7);
  EXPECT_GT(darkShare(at_consent), 0.8);
  EXPECT_TRUE(boxShown(at_consent, p.consent.find(StudyTargetAction::kAgree)));
  // The first task while its stroke is painted (5.3 s on): the sky, and the task's picture in
  // its place in the panel.
  const ImageRgba8 in_task = t.frameAt(6.0);
  EXPECT_LT(darkShare(in_task), 0.1) << "the sky fills the painting view";
  ASSERT_GT(p.task.image[2], p.task.image[0]);
  const glm::vec3 shown = meanIn(in_task, p.task.image[0], p.task.image[1], p.task.image[2],
                                 p.task.image[3]),
                  expected =
                      meanIn(p.picture, 0, 0, float(p.picture.width), float(p.picture.height));
  EXPECT_LT(glm::length(shown - expected), 20.0f)
      << "the reference picture's mean colour " << expected.r << "," << expected.g << ","
      << expected.b << "; the frame shows " << shown.r << "," << shown.g << "," << shown.b;
  // The questionnaire before its first answer (12.6 s): a form, the five answer boxes drawn;
  // the consent frame has no such boxes there.
  const ImageRgba8 at_questions = t.frameAt(12.3);
  EXPECT_GT(darkShare(at_questions), 0.5);  // (the answer boxes)
  int boxes_in_questions = 0, boxes_in_consent = 0;
  for (int value = 1; value <= 5; ++value) {
    const StudyTarget* answer = p.questionnaire.find(StudyTargetAction::kAnswer, value);
    ASSERT_TRUE(answer) << value;
    boxes_in_questions += boxShown(at_questions, answer);
    boxes_in_consent += boxShown(at_consent, answer);
  }
  EXPECT_EQ(boxes_in_questions, 5);
  EXPECT_LT(boxes_in_consent, 5);
  EXPECT_GT(glm::length(meanOf(at_questions) - meanOf(at_consent)), 0.5f)
      << "the consent and questionnaire frames differ";
}

TEST(StudyReplayFrames, TheFramesAreTheRunnersScreensAndTheTaskVolumesAreTheSame) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("cb_study_frames_" + std::to_string(::getpid())))
          .string();
  std::filesystem::remove_all(dir);
  Recorded recorded;
  ASSERT_NO_FATAL_FAILURE(runSession(dir, &recorded));

  const char* keep = std::getenv("CB_KEEP_FRAMES");
  Timeline timeline;
  timeline.frames = keep ? std::string(keep) : dir + "/frames";
  std::filesystem::remove_all(timeline.frames);
  test::CommandRun replay;
  ASSERT_NO_FATAL_FAILURE(replayFrames(recorded, timeline.frames, &replay));
  ASSERT_NO_FATAL_FAILURE(checkTimeline(recorded.folder, replay.out, &timeline));
  Pages pages;
  ASSERT_NO_FATAL_FAILURE(layOutPages(recorded.protocol, dir, &pages));
  ASSERT_NO_FATAL_FAILURE(checkFramesShowThePages(timeline, pages));
  if (!HasFailure() && !keep) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cb
