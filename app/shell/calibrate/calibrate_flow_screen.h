// A whole calibration as one pushable screen: wait for the pen, then either the N-point taps
// (targets → result → accept saves the profile, redo goes back to the targets) or the
// participant's press (light, firm). It journals what a re-fit needs (the device, the screen
// and targets as markers, raw samples, redo markers, the accepted profile or the session's
// pressure range) and reports its outcome through a callback. `cloudbrush calibrate` runs it on
// the frame loop; an operator panel can push it the same way.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/shell/calibrate/calibrate_screen.h"
#include "calibration/n_point_calibration.h"
#include "calibration/point_fit.h"
#include "calibration/pressure_range.h"

namespace cb {

class CalibrateWaitScreen;
class CalibratePressureScreen;
class CalibrateTargetsScreen;
class CalibrateResultScreen;

struct CalibrateOutcome {
  enum class Kind { kSaved, kPressureRange, kCancelled, kFailed };
  Kind kind = Kind::kFailed;
  std::string message;  // the saved path, the range's TOML, or why it failed
  std::optional<CalibrationFit> fit;
  std::vector<Tap> taps;
  std::string saved_path;
  PressureRangeFit pressure;
};

struct CalibrateFlowOptions {
  enum class Task { kTargets, kPressure };
  Task task = Task::kTargets;
  int targets = 9;  // 5 or 9 (targetLayout)
  PointFitKind fit = PointFitKind::kHomography;
  bool per_tool = false;              // the profile is for this pen's serial only
  bool auto_accept = false;           // accept the first fit after showing it once
  std::string config_dir, state_dir;  // where profiles are looked up and saved
  JournalWriter* journal = nullptr;   // the session's record (may be null)
  bool end_loop_when_done = true;     // the outcome ends the frame loop (a command); a pushed
                                      // screen leaves that to the callback
  bool esc_quits = true;              // Esc ends the loop (command); otherwise it cancels the flow
  std::string esc_returns_to;         // with !esc_quits: where Esc goes, in words ("the
                                      // operator panel"); the screens say so
  std::function<void(const std::string&)> log;  // progress lines
  std::function<void(const CalibrateOutcome&)> on_done;
};

// The journal markers of a calibration session (read back by `cloudbrush calibrate --journal`).
std::string calibrateScreenMarker(int width, int height);
std::string calibrateTargetMarker(size_t index, glm::dvec2 target);
inline constexpr const char* kCalibrateRedoMarker = "calibrate redo";

// The profile the taps are measured against: the one in force for `device` with its old
// correction removed. Messages (corrupt profiles, where it came from) go to `log`.
CalibrationProfile calibrationBaseProfile(const PenDeviceInfo& device, uint64_t tool_serial,
                                          const std::string& config_dir,
                                          const std::string& state_dir,
                                          const std::function<void(const std::string&)>& log);

class CalibrateFlowScreen : public Screen {
 public:
  enum class Stage { kWaitForPen, kPressure, kTargets, kResult, kDone };
  CalibrateFlowScreen(PenSource* pen, int width, int height, CalibrateFlowOptions options);
  ~CalibrateFlowScreen() override;

  const char* name() const override { return "calibrate"; }
  void onPenSamples(const std::vector<PenSample>& samples) override;
  void onCommand(Command command, int64_t t_ns) override;
  void onResize(int width, int height) override;
  std::string update(const FrameContext& frame) override;
  bool needsFrame() const override;
  bool draw(FrameContext& frame, std::string* error) override;
  void presented(const FrameContext& frame, double frame_ms) override;
  bool allowsQuit() const override { return options_.esc_quits; }

  Stage stage() const { return stage_; }
  // The words on the frame last drawn (what the person at the screen reads).
  std::vector<std::string> words() const { return context_.view.words(); }
  const std::optional<CalibrateOutcome>& outcome() const { return outcome_; }

 private:
  CalibrateScreen* current() const;
  void penArrived();
  void tapsDone(const std::vector<Tap>& taps);
  void resultChosen(bool accept);
  void redo();
  void finish(CalibrateOutcome outcome);

  CalibrateFlowOptions options_;
  CalibrateContext context_;
  Stage stage_ = Stage::kWaitForPen;
  PenDeviceInfo device_;
  CalibrationProfile base_;
  std::vector<Tap> taps_;
  std::optional<CalibrationFit> fit_;
  std::unique_ptr<CalibrateWaitScreen> wait_;
  std::unique_ptr<CalibratePressureScreen> pressure_;
  std::unique_ptr<CalibrateTargetsScreen> targets_;
  std::unique_ptr<CalibrateResultScreen> result_;
  std::optional<CalibrateOutcome> outcome_;
};

}  // namespace cb
