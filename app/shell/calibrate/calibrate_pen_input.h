// The calibration screens' pen: raw samples → journal (raw, so a record can be re-fitted) →
// Calibrator on the profile being measured against (its old correction removed) → pen events
// (pen_events.h, the one place that decides pen-down). Each event comes with the calibrated
// sample it was derived from, whose raw tablet millimetres are what a tap is measured in.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "app/shell/pen_events.h"
#include "calibration/calibrator.h"
#include "calibration/n_point_calibration.h"

namespace cb {

class JournalWriter;

struct CalibratePenEvent {
  PenEvent event;
  MappedSample sample;
};

class CalibratePenInput {
 public:
  // Maps `device` onto a width × height screen with `profile` (for the N-point fit: the profile
  // in force with its correction removed, calibration_profile.h). Called again, it starts over.
  void start(const CalibrationProfile& profile, const PenDeviceInfo& device, int width, int height);
  bool started() const { return calibrator_ != nullptr; }
  // Raw samples are appended to `journal` (may be null or closed) as they are fed.
  void setJournal(JournalWriter* journal) { journal_ = journal; }

  // Each sample is journalled, calibrated and its events handed to `on_event` before the next
  // sample is journalled, so what a handler journals (a marker) lands right after the sample
  // that caused it. Samples fed before start() are dropped.
  void feed(const std::vector<PenSample>& samples,
            const std::function<void(const CalibratePenEvent&)>& on_event);

  // Where the pen is (screen px, y down) and whether it is in range.
  glm::dvec2 cursor() const { return cursor_; }
  bool inRange() const { return in_range_; }
  bool down() const { return deriver_.down(); }
  uint64_t toolSerial() const { return tool_serial_; }
  int64_t lastSampleNs() const { return last_t_ns_; }
  const Calibrator* calibrator() const { return calibrator_.get(); }

 private:
  std::unique_ptr<Calibrator> calibrator_;
  PenEventDeriver deriver_;
  JournalWriter* journal_ = nullptr;
  glm::dvec2 cursor_{-100.0};
  bool in_range_ = false;
  uint64_t tool_serial_ = 0;
  int64_t last_t_ns_ = 0;
};

// A tap from pen events: down starts it, drags add to it, up ends it (TapCollector takes the
// median of the raw tablet positions in contact). Returns the tap when `e` ended one.
std::optional<glm::dvec2> collectTap(TapCollector& collector, const CalibratePenEvent& e);

}  // namespace cb
