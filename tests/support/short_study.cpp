#include "tests/support/short_study.h"

#include <gtest/gtest.h>

#include <cmath>

#include "app/session/synthetic_session.h"
#include "app/shell/study/study_page.h"
#include "app/study/study_run_state.h"
#include "drivers/core/journal.h"

namespace cb::test {

const char* const kShortStudyProtocol = R"(
[study]
name = "Short study"
version = "1"
[consent]
text = "A short session: two paintings, then three questions. Do you agree?"
[participants]
id_scheme = "counter"
prefix = "C"
digits = 2
[[venue]]
id = "lab"
name = "The test's machine"
[operator]
required = false
[introduction]
text = "Two short paintings, then three questions."
[tutorial]
minutes = 10
[[tutorial.step]]
instruction = "Start from an empty sky."
expect = ["cloud_empty == true"]
[free_drawing]
text = "Nothing to draw yet: a moment to get ready."
minutes = 0.03
[tasks]
order = "fixed"
minutes = 0.06
[[task]]
id = "first"
title = "First cloud"
image = "images/cloud1_duck.png"
save = ["journal", "volume_raw"]
[[task]]
id = "second"
title = "Second cloud"
image = "images/cloud2_photo1.png"
save = ["journal", "volume_raw"]
[questionnaire]
scale = ["strongly disagree", "disagree", "neutral", "agree", "strongly agree"]
[[item]]
id = "Q1"
text = "The session went on where it stopped."
[[item]]
id = "Q2"
text = "Nothing was lost."
[[item]]
id = "Q3"
text = "I would paint again."
)";

namespace {

constexpr int kW = kShortStudyWidth, kH = kShortStudyHeight;
constexpr int64_t kSecond = 1'000'000'000, kT0 = kShortStudyT0;

class PenScript {
 public:
  explicit PenScript(const PenDeviceInfo& tablet) : tablet_(tablet) {}
  // A tap in the middle of `target` at `t`.
  void tap(const StudyTarget* target, int64_t t) {
    ASSERT_TRUE(target);
    const float x = 0.5f * (target->x0 + target->x1), y = 0.5f * (target->y0 + target->y1);
    for (const PenSample& s : penTapSamples(tablet_, x, y, kW, kH, t)) add(s);
  }
  // Reference stroke `which` (referencePaintStrokes) from `t`; returns when it ended.
  int64_t stroke(size_t which, int64_t t) {
    for (const PenSample& s :
         syntheticPenSamples(referencePaintStrokes(kW, kH)[which], tablet_, kW, kH, 200.0, t)) {
      add(s);
      t = s.t_ns;
    }
    return t;
  }
  void add(const PenSample& s) {
    EXPECT_GT(s.t_ns, last_) << "samples in time order";
    last_ = s.t_ns;
    samples_.push_back(s);
  }
  const std::vector<PenSample>& samples() const { return samples_; }

 private:
  PenDeviceInfo tablet_;
  std::vector<PenSample> samples_;
  int64_t last_ = 0;
};

}  // namespace

// The pen of one participant: consent at 1 s, the code at 1.8 s, the introduction at 2.6 s (the
// tutorial step holds at once; the free drawing's 1.8 s pass without the pen), one stroke in
// the first task (from 5.3 s; the task runs from about 4.45 s to 8.05 s), another in the second
// (from 8.9 s; it ends at about 11.65 s), the three answers at 12.6, 13.4 and 14.2 s. Every
// stage change falls in most of a second without pen samples, so where a kill lands cannot move
// a sample across one.
void recordShortStudyPen(const StudyProtocol& protocol, const std::string& path) {
  const PenDeviceInfo tablet = syntheticTablet(kW, kH);
  PenScript pen(tablet);
  StudyRunState layout(protocol, 1, 0);
  // Laid out as the runner lays them out: texts measured with its font and glyphs.
  StudyPageInput input;
  std::string error;
  input.measure = studyPageFont(protocol, &error);
  ASSERT_TRUE(input.measure) << error;
  const auto page = [&] { return buildStudyPage(layout, input, kW, kH); };
  const auto at = [](double seconds) { return kT0 + int64_t(seconds * 1e9); };
  pen.tap(page().find(StudyTargetAction::kAgree), at(1.0));
  layout.agree(0);
  pen.tap(page().find(StudyTargetAction::kContinue), at(1.8));
  layout.proceed(0);
  ASSERT_EQ(layout.stage(), StudyStageKind::kIntroduction);
  pen.tap(page().find(StudyTargetAction::kContinue), at(2.6));
  layout.proceed(0);
  EXPECT_LT(pen.stroke(0, at(5.3)), at(7.0)) << "the first task's stroke ends a second early";
  EXPECT_LT(pen.stroke(1, at(8.9)), at(10.6)) << "the second task's stroke ends a second early";
  layout.completeTutorialStep(0);
  layout.closeStage(0);
  for (int i = 0; i < 3; ++i) {  // free drawing, the two tasks
    layout.tick(7 * kSecond * (i + 1));
    layout.closeStage(7 * kSecond * (i + 1));
  }
  ASSERT_EQ(layout.stage(), StudyStageKind::kQuestionnaire);
  const int answers[3] = {4, 2, 5};
  for (int i = 0; i < 3; ++i) {
    pen.tap(page().find(StudyTargetAction::kAnswer, answers[i]), at(12.6 + 0.8 * i));
    layout.answerItem(answers[i], 0);
  }
  JournalWriter journal;
  ASSERT_TRUE(journal.open(path)) << journal.error();
  const std::vector<uint8_t> device = encodeDeviceInfo(tablet);
  ASSERT_TRUE(journal.append(JournalRecordType::kDevice, kT0, device.data(), device.size()));
  for (const PenSample& s : pen.samples()) ASSERT_TRUE(journal.appendPenSample(s));
}

PenSample tabletSampleAt(const PenDeviceInfo& tablet, float x, float y, int w, int h, int64_t t_ns,
                         bool tip, bool proximity) {
  PenSample s;
  s.t_ns = t_ns;
  s.x_mm = double(x) * double(tablet.x_max) / tablet.x_res / w;
  s.y_mm = double(y) * double(tablet.y_max) / tablet.y_res / h;
  s.x_raw = int32_t(std::lround(s.x_mm * tablet.x_res));
  s.y_raw = int32_t(std::lround(s.y_mm * tablet.y_res));
  s.pressure_raw = tip ? int32_t(0.6f * float(tablet.pressure_max)) : 0;
  s.pressure = float(s.pressure_raw) / float(tablet.pressure_max);
  s.distance_raw = tip ? 0 : 10;
  s.distance = float(s.distance_raw) / float(tablet.distance_max);
  s.buttons = tip ? kPenTip : 0u;
  s.tool = proximity ? PenTool::kPen : PenTool::kNone;
  s.tool_id = proximity ? 0x802u : 0u;
  s.in_proximity = proximity;
  return s;
}

std::vector<PenSample> penTapSamples(const PenDeviceInfo& tablet, float x, float y, int w, int h,
                                     int64_t t_ns) {
  std::vector<PenSample> s;
  const int64_t dt = 5'000'000;
  for (int i = 0; i < 3; ++i)
    s.push_back(tabletSampleAt(tablet, x, y, w, h, t_ns += dt, false, true));
  for (int i = 0; i < 4; ++i)
    s.push_back(tabletSampleAt(tablet, x, y, w, h, t_ns += dt, true, true));
  for (int i = 0; i < 2; ++i)
    s.push_back(tabletSampleAt(tablet, x, y, w, h, t_ns += dt, false, true));
  s.push_back(tabletSampleAt(tablet, x, y, w, h, t_ns += dt, false, false));
  return s;
}

}  // namespace cb::test
