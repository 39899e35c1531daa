// The study runner's screen (StudyRunScreen) on a surfaceless test display, driven as FrameLoop
// drives it but on the test's clock: the session folder under a temporary directory, the
// painting session journalled into it, a pen (the synthetic tablet, connected, its samples handed
// in by the test; or a recorded journal played by the replay backend), and the protocol's state.
// Shared by the study screen tests (appendix_b_task_walk_test, study_run_slips_test,
// study_run_screen_test). CB_KEEP_FRAMES=DIR keeps the frames `keep` names.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/brush/synthetic_strokes.h"
#include "app/render/image_io.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/shell/study/study_run_screen.h"
#include "drivers/core/journal.h"
#include "drivers/replay/replay_pen_source.h"

namespace cb::test {

inline constexpr int64_t kRigSecond = 1'000'000'000;
inline constexpr int64_t kRigFrame = 16'666'667;  // 60 Hz

struct StudyRigOptions {
  int width = 1920, height = 1080;
  // A recorded pen journal (Device record and samples) played by the replay backend, one sample a
  // poll; empty: the synthetic tablet, connected, whose samples the test hands in.
  std::string pen_journal;
  // Kept frames are named CB_KEEP_FRAMES/<keep_prefix><name>.png, numbered in order when
  // `numbered` (<keep_prefix>NN_<name>.png).
  std::string keep_prefix;
  bool numbered = false;
  // The runner's options after the rig filled them (folder, participant, state and config dirs).
  std::function<void(StudyRunOptions&)> adjust;
};

class StudyScreenRig {
 public:
  ~StudyScreenRig();

  // The temporary directory (`name` + pid, emptied) and its session folder data/P01-test; a
  // recorded pen may be written into `dir` before start().
  void prepare(const std::string& name);
  // The display, renderer, session, journal, pen, state and screen. gtest failures (check with
  // ASSERT_NO_FATAL_FAILURE) when the display or renderer do not open.
  void start(StudyProtocol protocol, const StudyRigOptions& options = {});

  // Frames at `step_ns` each: at least `n`, and as many as `samples` need at `per_frame` a frame
  // (handed in before each frame's update). Stops when the screen ends the loop (`quit`).
  void frames(int n, int64_t step_ns = kRigFrame, std::vector<PenSample> samples = {},
              size_t per_frame = 3);
  // `samples` at `per_frame` a frame, then `settle` frames (-1: settle_frames).
  void pen(const std::vector<PenSample>& samples, size_t per_frame = 3, int settle = -1);
  // A synthetic stroke with the synthetic tablet, 200 samples a second from now.
  void stroke(const SyntheticStroke& s);
  // The recorded pen's next `count` samples (one stroke), at their own pace.
  void recordedStroke(size_t count);
  // A pen tap (hover in, tip down, lift, out) in the middle of the page's target, or at (x, y).
  void tap(StudyTargetAction action, int value = -1);
  void tapAt(float x, float y);
  // A tap on the on-screen keyboard's key that types `key`.
  void tapKey(const std::string& key);
  // A mouse click (button 1 down and up) in the middle of the page's target.
  void click(StudyTargetAction action);
  // Keys as the painter's --keys list names them, each a command and a frame.
  void keys(const char* list);
  // One more frame, kept as `name` when CB_KEEP_FRAMES is set.
  void keep(const std::string& name);

  // A label of the page drawn last containing `part`, or null; every label's text.
  const UiLabel* label(const std::string& part) const;
  bool shown(const std::string& part) const { return label(part) != nullptr; }
  std::string words() const;
  // The journal's Marker (or Sync) records' texts, in order.
  std::vector<std::string> markers();
  std::vector<std::string> syncMarkers();

  int w = 1920, h = 1080;
  int settle_frames = 2;  // frames after a tap's (or pen()'s) samples
  std::string dir, folder;
  std::unique_ptr<Display> display;
  VolumeRenderer renderer;
  std::unique_ptr<PaintSession> session;
  JournalWriter journal;
  PenDeviceInfo tablet;
  std::unique_ptr<ReplayPenSource> pen_source;
  StudyProtocol protocol;
  std::unique_ptr<StudyRunState> state;
  std::unique_ptr<StudyRunScreen> screen;
  int64_t now = 50 * kRigSecond;
  long frame_count = 0;
  std::string quit;  // what update() returned when the screen ended the loop

 private:
  std::string keep_prefix_;
  bool numbered_ = false;
  int kept_ = 0;
};

}  // namespace cb::test
