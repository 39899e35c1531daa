#include "tests/unit/shell/study/study_screen_rig.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/brush/synthetic_strokes.h"
#include "app/core/config_paths.h"
#include "app/session/synthetic_session.h"
#include "app/shell/keymap.h"
#include "tests/support/short_study.h"
#include "tests/support/test_display.h"

namespace cb::test {

StudyScreenRig::~StudyScreenRig() {
  screen.reset();  // before the session and display it uses
  if (!dir.empty()) std::filesystem::remove_all(dir);
}

void StudyScreenRig::prepare(const std::string& name) {
  dir = (std::filesystem::temp_directory_path() / (name + std::to_string(::getpid()))).string();
  std::filesystem::remove_all(dir);
  folder = dir + "/data/P01-test";
  std::filesystem::create_directories(folder);
  std::filesystem::create_directories(dir + "/state");
}

void StudyScreenRig::start(StudyProtocol p, const StudyRigOptions& options) {
  protocol = std::move(p);
  w = options.width, h = options.height;
  keep_prefix_ = options.keep_prefix, numbered_ = options.numbered;
  tablet = syntheticTablet(w, h);
  std::string error;
  display = openTestDisplay(w, h, &error);
  ASSERT_TRUE(display) << error;
  ASSERT_TRUE(renderer.init(&error)) << error;
  session = std::make_unique<PaintSession>(PaintSessionSettings{w, h}, loadDefaultBrushConfig(),
                                           loadMappingConfig(configFile("mapping.toml")));
  session->setQuietMapping(true);
  ASSERT_TRUE(journal.open(folder + "/session.cbj")) << journal.error();
  session->recordTo(&journal, now);
  ReplayOptions replay;
  replay.realtime = false;
  if (!options.pen_journal.empty()) {
    replay.batch = 1;
    pen_source = std::make_unique<ReplayPenSource>(options.pen_journal, replay);
  } else {
    // The synthetic tablet, connected (the test hands its samples to the screen).
    std::vector<JournalRecord> records(2);
    records[0].type = JournalRecordType::kDevice;
    records[0].payload = encodeDeviceInfo(tablet);
    records[1].type = JournalRecordType::kPenSample;
    records[1].payload = encodePenSample(tabletSampleAt(tablet, 1, 1, w, h, 0, false, false));
    pen_source = std::make_unique<ReplayPenSource>(records, replay);
  }
  state = std::make_unique<StudyRunState>(protocol, 1, now);
  StudyRunOptions run;
  run.folder = folder;
  run.end_seconds = 1.0;
  run.info.protocol_name = protocol.name;
  run.info.participant_id = state->participantId();
  run.info.participant_number = 1;
  run.info.anchor_monotonic_ns = now;
  run.paint.config_dir = dir + "/config";
  run.paint.state_dir = dir + "/state";
  if (options.adjust) options.adjust(run);
  screen = std::make_unique<StudyRunScreen>(*display, renderer, *session, pen_source.get(),
                                            &journal, *state, run);
}

void StudyScreenRig::frames(int n, int64_t step_ns, std::vector<PenSample> samples,
                            size_t per_frame) {
  size_t next = 0;
  for (int i = 0; (i < n || next < samples.size()) && quit.empty(); ++i) {
    now += step_ns;
    const size_t take = std::min(per_frame, samples.size() - next);
    screen->onPenSamples(
        std::vector<PenSample>(samples.begin() + long(next), samples.begin() + long(next + take)));
    next += take;
    FrameContext frame{*display, w, h, frame_count, now, double(step_ns) / 1e9};
    quit = screen->update(frame);
    if (!quit.empty()) return;
    std::string error;
    ASSERT_TRUE(screen->draw(frame, &error)) << error;
    ASSERT_TRUE(display->present(&error)) << error;
    ++frame_count;
  }
}

void StudyScreenRig::pen(const std::vector<PenSample>& samples, size_t per_frame, int settle) {
  frames(0, kRigFrame, samples, per_frame);
  frames(settle >= 0 ? settle : settle_frames);
}

void StudyScreenRig::stroke(const SyntheticStroke& s) {
  pen(syntheticPenSamples(s, tablet, w, h, 200.0, now));
}

void StudyScreenRig::recordedStroke(size_t count) {
  std::vector<PenSample> samples;
  for (size_t i = 0; i < count; ++i) pen_source->poll(0, samples);
  frames(0, kRigFrame, samples);
}

void StudyScreenRig::tap(StudyTargetAction action, int value) {
  const StudyTarget* t = screen->page().find(action, value);
  ASSERT_TRUE(t) << "no target " << int(action) << " value " << value
                 << "; the page waits for: " << state->waitingFor(now);
  tapAt(0.5f * (t->x0 + t->x1), 0.5f * (t->y0 + t->y1));
}

void StudyScreenRig::tapAt(float x, float y) {
  pen(penTapSamples(tablet, x, y, w, h, now));
}

void StudyScreenRig::tapKey(const std::string& key) {
  for (const StudyTarget& t : screen->page().targets)
    if (t.action == StudyTargetAction::kKey && t.text == key)
      return tapAt(0.5f * (t.x0 + t.x1), 0.5f * (t.y0 + t.y1));
  FAIL() << "no key " << key;
}

void StudyScreenRig::click(StudyTargetAction action) {
  const StudyTarget* t = screen->page().find(action);
  ASSERT_TRUE(t) << "no target " << int(action) << " on the page";
  DisplayEvent e;
  e.x = 0.5f * (t->x0 + t->x1), e.y = 0.5f * (t->y0 + t->y1), e.button = 1;
  e.kind = DisplayEvent::Kind::PointerDown;
  screen->onPointer(e);
  e.kind = DisplayEvent::Kind::PointerUp;
  screen->onPointer(e);
  frames(2);
}

void StudyScreenRig::keys(const char* list) {
  std::vector<DisplayEvent> events;
  std::string error;
  ASSERT_TRUE(parseKeyList(list, &events, &error)) << error;
  for (const DisplayEvent& e : events) {
    const std::optional<Command> command = commandFor(e);
    ASSERT_TRUE(command) << list;
    screen->onCommand(*command, now);
    frames(1);
  }
  frames(1);
}

void StudyScreenRig::keep(const std::string& name) {
  frames(1);
  const char* out = std::getenv("CB_KEEP_FRAMES");
  if (!out || !quit.empty()) return;
  char number[16] = "";
  if (numbered_) std::snprintf(number, sizeof number, "%02d_", ++kept_);
  writePng(std::string(out) + "/" + keep_prefix_ + number + name + ".png",
           readFramebufferRgba8(display->framebuffer(), w, h));
}

const UiLabel* StudyScreenRig::label(const std::string& part) const {
  for (const UiLabel& l : screen->page().labels)
    if (l.text.find(part) != std::string::npos) return &l;
  return nullptr;
}

std::string StudyScreenRig::words() const {
  std::string all;
  for (const UiLabel& l : screen->page().labels) all += "[" + l.text + "] ";
  return all;
}

std::vector<std::string> StudyScreenRig::markers() {
  journal.sync();
  std::vector<std::string> out;
  for (const JournalRecord& r : readJournal(folder + "/session.cbj").records)
    if (r.type == JournalRecordType::kMarker) out.emplace_back(r.text());
  return out;
}

std::vector<std::string> StudyScreenRig::syncMarkers() {
  journal.sync();
  std::vector<std::string> out;
  for (const JournalRecord& r : readJournal(folder + "/session.cbj").records)
    if (r.type == JournalRecordType::kSync) out.emplace_back(r.text());
  return out;
}

}  // namespace cb::test
