#include "app/shell/calibrate/calibrate_flow_screen.h"

#include <cstdio>

#include "app/shell/calibrate/calibrate_pressure_screen.h"
#include "app/shell/calibrate/calibrate_result_screen.h"
#include "app/shell/calibrate/calibrate_targets_screen.h"
#include "app/shell/calibrate/calibrate_wait_screen.h"
#include "calibration/profile_store.h"
#include "drivers/core/journal.h"
#include "drivers/core/pen_source.h"

namespace cb {

std::string calibrateScreenMarker(int width, int height) {
  return "calibrate screen " + std::to_string(width) + " " + std::to_string(height);
}

std::string calibrateTargetMarker(size_t index, glm::dvec2 target) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "calibrate target %zu %.17g %.17g", index, target.x, target.y);
  return buf;
}

CalibrationProfile calibrationBaseProfile(const PenDeviceInfo& device, uint64_t tool_serial,
                                          const std::string& config_dir,
                                          const std::string& state_dir,
                                          const std::function<void(const std::string&)>& log) {
  ProfileSelection sel = selectProfile(device, tool_serial, config_dir, state_dir);
  if (log) {
    for (const auto& m : sel.messages) log(m);
    log("area mapping from " + sel.source);
  }
  CalibrationProfile p = sel.profile;
  p.fit_kind = PointFitKind::kNone;
  p.correction = glm::dmat3(1.0);
  p.fit_rms_px = p.fit_max_px = 0.0;
  p.fit_points = 0;
  return p;
}

CalibrateFlowScreen::CalibrateFlowScreen(PenSource* pen, int width, int height,
                                         CalibrateFlowOptions options)
    : options_(std::move(options)) {
  context_.pen = pen;
  context_.width = width;
  context_.height = height;
  context_.journal = options_.journal;
  context_.log = options_.log;
  if (!options_.esc_quits)
    context_.esc_hint =
        "Esc goes back" +
        (options_.esc_returns_to.empty() ? std::string() : " to " + options_.esc_returns_to) +
        " without saving.";
  wait_ = std::make_unique<CalibrateWaitScreen>(context_,
                                                [this](bool connected, const std::string& why) {
                                                  if (connected) return penArrived();
                                                  CalibrateOutcome o;
                                                  o.message = why;
                                                  finish(o);
                                                });
}

CalibrateFlowScreen::~CalibrateFlowScreen() = default;

CalibrateScreen* CalibrateFlowScreen::current() const {
  switch (stage_) {
    case Stage::kWaitForPen:
      return wait_.get();
    case Stage::kPressure:
      return pressure_.get();
    case Stage::kTargets:
      return targets_.get();
    case Stage::kResult:
      return result_.get();
    case Stage::kDone:
      return nullptr;
  }
  return nullptr;
}

void CalibrateFlowScreen::finish(CalibrateOutcome outcome) {
  if (stage_ == Stage::kDone) return;
  stage_ = Stage::kDone;
  context_.changed = true;
  // The record ends with the outcome: samples after it (the rest of a batch) are not journalled.
  context_.input.setJournal(nullptr);
  outcome_ = std::move(outcome);
  if (options_.on_done) options_.on_done(*outcome_);
}

void CalibrateFlowScreen::penArrived() {
  device_ = context_.pen->deviceInfo();
  base_ = calibrationBaseProfile(device_, 0, options_.config_dir, options_.state_dir, context_.log);
  context_.input.start(base_, device_, context_.width, context_.height);
  context_.input.setJournal(options_.journal);
  if (options_.journal) {
    const std::vector<uint8_t> bytes = encodeDeviceInfo(device_);
    options_.journal->append(JournalRecordType::kDevice, 0, bytes.data(), bytes.size());
  }
  if (options_.task == CalibrateFlowOptions::Task::kPressure) {
    if (device_.pressure_max <= 0) {
      CalibrateOutcome o;
      o.message = "this pen reports no pressure";
      return finish(o);
    }
    context_.say("press lightly and hold (0.5 s), then lift");
    pressure_ = std::make_unique<CalibratePressureScreen>(
        context_, base_.pressure.light_target, [this](const PressureRangeFit& fit) {
          const std::string text = pressureRangeToToml(*fit.range);
          if (options_.journal)
            options_.journal->append(JournalRecordType::kSession, context_.input.lastSampleNs(),
                                     text);
          char line[128];
          std::snprintf(line, sizeof line, "light press %.3f, firm press %.3f (nib offset %.3f)",
                        fit.light, fit.firm, context_.input.calibrator()->nibOffset());
          context_.say(line);
          CalibrateOutcome o;
          o.kind = CalibrateOutcome::Kind::kPressureRange;
          o.message = text;
          o.pressure = fit;
          finish(o);
        });
    stage_ = Stage::kPressure;
    context_.changed = true;
    return;
  }
  const std::vector<glm::dvec2> targets =
      targetLayout(options_.targets, context_.width, context_.height);
  if (options_.journal) {
    options_.journal->append(JournalRecordType::kMarker, 0,
                             calibrateScreenMarker(context_.width, context_.height));
    for (size_t i = 0; i < targets.size(); ++i)
      options_.journal->append(JournalRecordType::kMarker, 0, calibrateTargetMarker(i, targets[i]));
  }
  targets_ = std::make_unique<CalibrateTargetsScreen>(
      context_, targets, [this](const std::vector<Tap>& taps) { tapsDone(taps); });
  stage_ = Stage::kTargets;
  context_.changed = true;
}

void CalibrateFlowScreen::redo() {
  if (options_.journal)
    options_.journal->append(JournalRecordType::kMarker, context_.input.lastSampleNs(),
                             kCalibrateRedoMarker);
  taps_.clear();
  fit_.reset();
  targets_->restart();
  stage_ = Stage::kTargets;
  context_.changed = true;
}

void CalibrateFlowScreen::tapsDone(const std::vector<Tap>& taps) {
  taps_ = taps;
  const uint64_t tool = options_.per_tool ? context_.input.toolSerial() : 0;
  fit_ = fitCalibration(base_, device_, tool, context_.width, context_.height, taps_, options_.fit);
  if (!fit_->ok) {
    context_.say(fit_->error + "; tap the targets again");
    return redo();
  }
  context_.say(describeFit(*fit_, taps_));
  if (!options_.auto_accept)
    context_.say("tap the green box (or press Space) to accept, the orange box to redo");
  result_ = std::make_unique<CalibrateResultScreen>(
      context_, *fit_, taps_, context_.input.calibrator()->areaTransform(), options_.auto_accept,
      [this](CalibrateResultScreen::Choice choice) {
        resultChosen(choice == CalibrateResultScreen::Choice::kAccept);
      });
  stage_ = Stage::kResult;
  context_.changed = true;
}

void CalibrateFlowScreen::resultChosen(bool accept) {
  if (!accept) {
    context_.say("redo");
    return redo();
  }
  if (options_.journal)
    options_.journal->append(JournalRecordType::kCalibration, context_.input.lastSampleNs(),
                             formatCalibrationProfile(fit_->profile));
  CalibrateOutcome o;
  o.fit = fit_;
  o.taps = taps_;
  std::string error;
  o.saved_path = saveProfile(fit_->profile, options_.state_dir, &error);
  if (o.saved_path.empty()) {
    o.message = error;
  } else {
    o.kind = CalibrateOutcome::Kind::kSaved;
    o.message = "saved " + o.saved_path;
    context_.say(o.message);
  }
  finish(o);
}

void CalibrateFlowScreen::onPenSamples(const std::vector<PenSample>& samples) {
  if (stage_ == Stage::kWaitForPen) wait_->check();
  if (!samples.empty()) context_.changed = true;
  // Event by event, so the events after the one that completed a screen go to the next.
  context_.input.feed(samples, [this](const CalibratePenEvent& e) {
    if (CalibrateScreen* screen = current()) screen->onPenEvent(e);
  });
}

void CalibrateFlowScreen::onCommand(Command command, int64_t t_ns) {
  context_.changed = true;
  if (command == Command::kQuit) {
    CalibrateOutcome o;
    o.kind = CalibrateOutcome::Kind::kCancelled;
    o.message = "left without saving";
    return finish(o);
  }
  if (CalibrateScreen* screen = current()) screen->onCommand(command, t_ns);
}

void CalibrateFlowScreen::onResize(int width, int height) {
  // The targets are laid out when the pen arrives; a later resize keeps them.
  if (stage_ == Stage::kWaitForPen) {
    context_.width = width;
    context_.height = height;
  }
}

std::string CalibrateFlowScreen::update(const FrameContext& frame) {
  if (CalibrateScreen* screen = current()) screen->update(frame);
  if (stage_ != Stage::kDone && stage_ != Stage::kWaitForPen && context_.pen &&
      context_.pen->connection() == PenConnection::kFinished &&
      !(stage_ == Stage::kResult && options_.auto_accept)) {
    // A replay that ended before the calibration did.
    CalibrateOutcome o;
    const size_t made =
        stage_ == Stage::kResult ? taps_.size() : (targets_ ? targets_->tapsMade() : 0);
    o.message = stage_ == Stage::kPressure
                    ? std::string("the replay ended before both presses")
                    : "the replay ended with " + std::to_string(made) + " of " +
                          std::to_string(options_.targets) + " taps";
    finish(o);
  }
  if (stage_ == Stage::kDone && options_.end_loop_when_done)
    return "calibration " + [&] {
      switch (outcome_->kind) {
        case CalibrateOutcome::Kind::kSaved:
          return std::string("saved");
        case CalibrateOutcome::Kind::kPressureRange:
          return std::string("pressure range set");
        case CalibrateOutcome::Kind::kCancelled:
          return std::string("cancelled");
        case CalibrateOutcome::Kind::kFailed:
          break;
      }
      return std::string("failed");
    }();
  return "";
}

bool CalibrateFlowScreen::needsFrame() const {
  const CalibrateScreen* screen = current();
  return screen ? screen->needsFrame() : false;
}

bool CalibrateFlowScreen::draw(FrameContext& frame, std::string* error) {
  CalibrateScreen* screen = current();
  context_.changed = false;
  return screen ? screen->draw(frame, error) : true;
}

void CalibrateFlowScreen::presented(const FrameContext& frame, double frame_ms) {
  if (CalibrateScreen* screen = current()) screen->presented(frame, frame_ms);
}

}  // namespace cb
