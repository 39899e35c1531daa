// PaintSession: the painting workflow without a display (DESIGN.md "One data flow"). Raw pen
// samples go through the calibration in force (calibration/), the stroke engine draws the live
// footprint (thesis §3.4, §5.3.1), and at tip-up the stroke mapper turns the footprint into voxels
// (thesis §6: HMM or RMM) merged into the session's Volume. Every input that changes the result
// is recorded, in order, to an optional JournalWriter: the session settings, the pen device, the
// calibration profile (as a Calibration record), raw samples and UI changes (camera, brush,
// mapping method). Replaying those records into a fresh session (applyRecord) repeats the session
// exactly: the stroke index seeds all randomness of brush and mapping, and the mapping reduces in
// chunk order, so the volume is byte-identical on any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "app/brush/brush_config.h"
#include "app/brush/footprint_rect.h"
#include "app/brush/stroke_engine.h"
#include "app/mapping/mapping_config.h"
#include "app/mapping/stroke_mapper.h"
#include "app/scene/camera.h"
#include "app/scene/canvas.h"
#include "app/volume/volume.h"
#include "calibration/calibration_profile.h"
#include "calibration/calibrator.h"
#include "drivers/core/journal.h"

namespace cb {

// What a session needs before the first sample; journalled as the Session record.
struct PaintSessionSettings {
  int screen_width = 1280, screen_height = 720;  // the display the pen maps to (pixels)
  int grid = 128;                                // volume resolution grid³
};

// The Session record's text ("key = value" lines, TOML) and its parser. The parser names the
// offending line in *error.
std::string formatSessionSettings(const PaintSessionSettings& settings);
bool parseSessionSettings(std::string_view text, PaintSessionSettings* settings,
                          std::string* error);

// What one pen sample did.
struct SampleOutcome {
  MappedSample mapped;
  FootprintRect changed;       // footprint pixels redrawn by this sample (empty: none)
  bool stroke_began = false;   // this sample started a stroke (a fresh footprint)
  bool stroke_mapped = false;  // this sample ended a stroke and it was mapped into the volume
  MappingReport mapping;       // valid when stroke_mapped
  uint32_t stroke_index = 0;   // of the mapped stroke
};

class PaintSession {
 public:
  PaintSession(const PaintSessionSettings& settings, const BrushConfig& brush,
               const MappingConfig& mapping);

  // Records everything from now on into `journal` (not owned; null stops recording). Writes
  // the Session record at once, and the device and calibration when already set.
  void recordTo(JournalWriter* journal, int64_t t_ns);

  // The pen that samples come from and the calibration to apply to them. Either change builds a
  // fresh Calibrator at the next sample (filters restart).
  void setDevice(const PenDeviceInfo& device, int64_t t_ns);
  void setCalibration(const CalibrationProfile& profile, int64_t t_ns);

  // One raw sample through calibration, brush and (at tip-up) mapping. Samples arriving before a
  // device is set cannot be interpreted: they are journalled, counted and otherwise ignored.
  SampleOutcome feed(const PenSample& sample);

  // UI changes, each journalled as a "key=value" Ui record and taking effect for the next stroke:
  //   camera_orbit=DEG   paint view = Camera::reference().orbited(DEG)
  //   brush=2d|3d|skeleton
  //   method=hybrid|ray-marching
  // False with *error naming the key or value on bad input (nothing is recorded then).
  bool applyUi(const std::string& key_value, int64_t t_ns, std::string* error);

  // Replay: applies one journal record as if it happened now (Session records must match the
  // settings this session was made with; Marker/Mode records are ignored). False with *error
  // naming the record's problem; the caller decides whether to go on.
  bool applyRecord(const JournalRecord& record, SampleOutcome* outcome, std::string* error);

  const Volume& volume() const { return volume_; }
  Volume& volume() { return volume_; }
  const StrokeEngine& engine() const { return engine_; }
  const Camera& camera() const { return camera_; }
  float cameraOrbitDegrees() const { return orbit_degrees_; }
  const Canvas& canvas() const { return canvas_; }
  const PaintSessionSettings& settings() const { return settings_; }
  int footprintWidth() const { return footprint_w_; }
  int footprintHeight() const { return footprint_h_; }
  uint32_t strokesMapped() const { return strokes_mapped_; }
  // The calibration in force (built-in defaults until setCalibration).
  const CalibrationProfile& calibration() const { return profile_; }
  const std::string& calibratorError() const { return calibrator_error_; }
  uint64_t samplesWithoutDevice() const { return samples_without_device_; }
  void setQuietMapping(bool quiet) { mapper_.setQuiet(quiet); }
  // The circles the hybrid mapping grew for the last mapped stroke (footprint pixels; empty
  // after a ray-marching stroke), for the C overlay.
  const std::vector<Circle>& lastCircles() const { return mapper_.lastCircles(); }
  BrushKind selectedBrush() const { return engine_.selectedBrush(); }
  MappingMethod mappingMethod() const { return method_; }

 private:
  void journalText(JournalRecordType type, int64_t t_ns, const std::string& text);
  void applyView();

  PaintSessionSettings settings_;
  int footprint_w_, footprint_h_;
  Volume volume_;
  StrokeEngine engine_;
  StrokeMapper mapper_;
  MappingMethod method_;
  CalibrationProfile profile_;
  std::optional<PenDeviceInfo> device_;
  std::unique_ptr<Calibrator> calibrator_;
  std::string calibrator_error_;
  Camera camera_ = Camera::reference();
  float orbit_degrees_ = 0.0f;
  Canvas canvas_;
  uint32_t strokes_mapped_ = 0;
  uint64_t samples_without_device_ = 0;
  JournalWriter* journal_ = nullptr;
};

}  // namespace cb
