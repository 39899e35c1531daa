// A short study session for the tests of `cloudbrush study run` and of its replay: a protocol
// (consent, the participant's code, an introduction, a one-step tutorial that holds at once (an
// empty sky), 1.8 s of free drawing, two tasks of 3.6 s, three Likert items) and one
// participant's recorded pen, which taps the runner's own targets (measured with its font, laid out
// by app/shell/study/study_page.h for a kShortStudyWidth × kShortStudyHeight screen) and paints one
// stroke in each task.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/study/protocol.h"
#include "drivers/core/pen_sample.h"

namespace cb::test {

constexpr int kShortStudyWidth = 512, kShortStudyHeight = 288;
constexpr int64_t kShortStudyT0 = 5'000'000'000;  // the pen journal's first time (ns)

// The protocol's TOML (its pictures are config/study/images/..., relative to the file).
extern const char* const kShortStudyProtocol;

// The pen of participant 1, from kShortStudyT0 (times in seconds after it): consent at 1 s, the
// code at 1.8 s, the introduction at 2.6 s (the tutorial step holds at once; the free drawing's
// 1.8 s pass without the pen), one stroke in the first task (from 5.3 s; the task runs from
// about 4.45 s to 8.05 s), another in the second (from 8.9 s; it ends at about 11.65 s), the
// answers 4, 2, 5 at 12.6, 13.4 and 14.2 s. Every stage change falls in most of a second
// without pen samples. Written to `path` as a journal (a Device record and the samples); gtest
// assertions on failure.
void recordShortStudyPen(const StudyProtocol& protocol, const std::string& path);

// One raw sample of `tablet` at pixel (x, y) of a w × h screen mapped over its whole area: tip
// down at pressure 0.6, or hovering 10 units above; a pen (tool id 0x802) in proximity, or none.
PenSample tabletSampleAt(const PenDeviceInfo& tablet, float x, float y, int w, int h, int64_t t_ns,
                         bool tip, bool proximity);
// A pen tap there, 5 ms a sample after t_ns: hover in (3), tip down (4), lifted (2), out (1).
std::vector<PenSample> penTapSamples(const PenDeviceInfo& tablet, float x, float y, int w, int h,
                                     int64_t t_ns);

}  // namespace cb::test
