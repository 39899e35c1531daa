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
#include <functional>
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
#include "app/scene/light.h"
#include "app/session/history.h"
#include "app/session/sync_marker_sender.h"
#include "app/session/ui_change.h"
#include "app/tools/cloud_animation.h"
#include "app/volume/sky_extent.h"
#include "app/volume/volume.h"
#include "calibration/calibration_profile.h"
#include "calibration/calibrator.h"
#include "drivers/core/journal.h"
#include "drivers/core/journal_frame.h"

namespace cb {

// What a session needs before the first sample; journalled as the Session record.
struct PaintSessionSettings {
  int screen_width = 1280, screen_height = 720;  // the display the pen maps to (pixels)
  int grid = 128;                                // voxels along each axis of the home box
  // Home boxes across the sky in x and z (sky_extent.h): the canvas spans the whole sky. A
  // Session record without `sky_span` is from the one-box sky (kLegacySkySpan), so old journals
  // replay in the box they were painted in, their strokes clipped to it as they were then.
  int sky_span = kDefaultSkySpan;
  // The sky grows with what is painted: a stroke reaching past its edge first widens it, by
  // whole home boxes about the home box, up to this many across (widestSkySpan: the volume's
  // limits and the grid may allow fewer). A Session record without `sky_max_span` is from a sky
  // that did not grow (sky_span), so its strokes replay clipped to it as they were then.
  int sky_max_span = kMaxSkySpan;
  // A placed picture or model (ui::PlaceShape) grows the sky as a stroke does, to hold where it
  // can write (app/tools pictureReach, modelReach). A Session record without
  // `placements_grow_sky` is from before they did (journal specification 1.4 and older), so its
  // placements replay clipped to the sky as they were then.
  bool placements_grow_sky = true;
  // Ink in the veil is left out (README: "veiled so ink that cannot land shows at once"): before
  // a finished stroke is mapped, its footprint pixels whose rays cannot meet the canvas inside
  // the sky as wide as it may grow (app/scene/drawable_region.h, in the stroke's own view) are
  // cleared, so only what lands is mapped and only that grows the sky. A Session record without
  // `veil_ink_left_out` is from before (journal specification 1.8 and older): its veiled ink
  // replays onto the mapping's fallback plane, growing the sky to its widest, as it was recorded.
  bool veil_ink_left_out = true;
  // Whether a placement grows this session's sky: only a sky that may grow at all.
  bool placementsGrowSky() const { return placements_grow_sky && sky_max_span > sky_span; }
  // The sky the session starts with.
  SkyExtent skyExtent() const { return {grid, sky_span}; }
  // Journal format of UI changes: 1 = the first landing (no modes; the paint view is
  // Camera::reference() unless a camera_orbit record says otherwise), 2 = typed changes with
  // modes and history (the paint view starts at defaultPaintCamera()). A Session record without
  // `format` is 1, so old journals replay as they did.
  int format = 2;
  // A stroke still open after this long ends by itself (thesis §7.7.5 problem 3: strokes left
  // open by a pen resting on the tablet). Held still (moving < 2 px) or touching only lightly
  // (held down by the contact hysteresis alone, MappedSample::light_contact) for the time given;
  // 0 disables. Journalled with the session, so replay ends the same strokes.
  int auto_end_still_ms = 2000;
  int auto_end_light_ms = 800;
};

// The painter's starting view for a session of `format` (see PaintSessionSettings).
Camera initialPaintCamera(const PaintSessionSettings& settings);

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
  bool erased = false;         // this sample rubbed out some cloud (erase mode, rub-out)
  bool auto_ended = false;     // the open stroke ended by itself (held still or touched lightly)
  long long veil_pixels = 0;   // inked footprint pixels in the veil, left out of the mapped stroke
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
  // Carries on recording a resumed session (session_resume.h) into `journal`, which already holds
  // its starting state: nothing is written now. Until the next pen sample, a setDevice or
  // setCalibration that repeats what is in force (the painter selects the pen again as it
  // starts) is not a change: the calibrator keeps its state, as in the session before the crash.
  void resumeRecordingTo(JournalWriter* journal);

  // The configuration in force, journalled as Settings records (JOURNAL.md): brush.toml and
  // mapping.toml as this session was made with, render.toml as set here (the painter's render
  // settings; the volume does not depend on them). recordTo writes all three; setting the render
  // settings while recording writes them again. A replay uses the recorded brush and mapping,
  // not the replaying machine's (session_replay.h).
  const BrushConfig& brushConfig() const { return brush_config_; }
  const MappingConfig& mappingConfig() const { return mapping_config_; }
  void setRenderSettings(const std::string& render_toml, int64_t t_ns);
  const std::string& renderSettings() const { return render_settings_; }  // empty: none recorded

  // Sync markers: task and stroke boundaries, journalled as Sync records and, when a
  // sender is set (not owned; null: none), sent as UDP datagrams at once. The session marks
  // stroke_begin and stroke_end (label: the stroke index) itself, stroke_end before the stroke
  // is mapped; the study runner marks its sessions, stages, tasks and answers. A marker's
  // monotonic time is its event's (t_ns); its wall time is the wall clock at that event: now
  // minus the event's age on the session's clock (setSyncClock; without one, CLOCK_MONOTONIC,
  // which live pen timestamps use).
  void setSyncSender(SyncMarkerSender* sender) { sync_sender_ = sender; }
  void setSyncClock(std::function<int64_t()> now_ns) { sync_now_ns_ = std::move(now_ns); }
  // Leave out of the journal what is measured at run time (each stroke's mapping time; sync
  // markers' wall clock, written as 0), so the same input writes the same bytes: a generated
  // journal such as the kiosk's bundled attract loop.
  void setReproducibleRecord(bool on) { reproducible_record_ = on; }
  void markSync(const std::string& kind, const std::string& label, int64_t t_ns);
  uint64_t syncMarkers() const { return sync_seq_; }

  // The pen that samples come from and the calibration to apply to them. Either change builds a
  // fresh Calibrator at the next sample (filters restart).
  void setDevice(const PenDeviceInfo& device, int64_t t_ns);
  void setCalibration(const CalibrationProfile& profile, int64_t t_ns);

  // One raw sample through calibration, brush and (at tip-up) mapping. Samples arriving before a
  // device is set cannot be interpreted: they are journalled, counted and otherwise ignored.
  SampleOutcome feed(const PenSample& sample);

  // A typed UI change (ui_change.h): applied, journalled and, when it changes the scene or the
  // cloud, recorded as a history step. Camera, canvas, brush and mapping take effect from the
  // next stroke; a mode change ends a stroke in progress first. False with *error when the change
  // cannot apply now (undo with nothing to undo, ...); nothing is journalled then.
  bool apply(const UiChange& change, int64_t t_ns, std::string* error = nullptr);

  // The painter's animations: a morph or wind animated on a copy of the cloud is
  // committed as the frame shown. `change` (ui::ApplyMorph or ui::ApplyWind) names how to
  // recompute it, `shown` is the frame on the tool's window (cloud_animation.h, tool_window.h:
  // the whole cloud in a one-box sky); the window of the cloud becomes `shown` as one history
  // step and one journal record (replay recomputes the frame from the record through apply()).
  // False with *error, nothing changed, when `shown` does not fit the cloud there or a stroke is
  // open.
  bool commitAnimation(const UiChange& change, const WindowFrame& shown, int64_t t_ns,
                       std::string* error);

  // Where the vacuum sphere sits for a pen at this sample (§3.5.1, Fig. 3.5): x/z where the
  // pen's ray meets the canvas mid-plane, the height from the pressure (0 = the bottom of the
  // volume, 1 = its top). False when the ray misses the plane.
  bool vacuumCentre(const MappedSample& sample, glm::vec3* centre) const;
  float eraseDiameter(EraseTool tool) const {
    return tool == EraseTool::kVacuum ? vacuum_diameter_ : rubout_diameter_;
  }
  // The rub-out cylinder's diameter at this pressure (§3.5.2: it varies with pressure; pens
  // without pressure report contact as full pressure).
  float rubOutDiameterAt(float pressure) const;

  // One presented frame's timing (drivers/core/journal_frame.h) as a Frame record: a
  // measurement of this run, which a replay skips.
  void journalFrame(const FrameRecord& record);
  // Replay: applies one journal record as if it happened now (Session records must match the
  // settings this session was made with; Marker/Mode records are ignored). False with *error
  // naming the record's problem; the caller decides whether to go on.
  bool applyRecord(const JournalRecord& record, SampleOutcome* outcome, std::string* error);

  // The sky as it is now: the starting extent (settings) grown to hold what was painted.
  const SkyExtent& sky() const { return sky_; }
  // The widest sky this session may grow to: where a stroke can land.
  SkyExtent reachableSky() const { return {sky_.grid, widest_span_}; }
  // How often the sky grew (for a stroke or a placement), and the mapped stroke that grew it last
  // (0: none).
  uint32_t skyGrowths() const { return sky_growths_; }
  uint32_t lastGrowthStroke() const { return last_growth_stroke_; }

  const Volume& volume() const { return volume_; }
  Volume& volume() { return volume_; }
  const StrokeEngine& engine() const { return engine_; }
  const Camera& camera() const { return scene_.camera; }
  const Canvas& canvas() const { return scene_.canvas; }
  const Light& light() const { return scene_.light; }
  const SceneState& scene() const { return scene_; }
  Mode mode() const { return mode_; }
  bool penCaptured() const { return pen_captured_; }
  // The painter's pen menu is shown (ui::ShowMenu; the screen draws it from here).
  bool menuOpen() const { return menu_open_; }
  const std::string& styleName() const { return style_; }
  // The render style before anything is recorded (config/render.toml); journalled with the
  // starting state.
  void setStartingStyle(const std::string& name) { style_ = name; }
  EraseTool eraseTool() const { return erase_tool_; }
  const History& history() const { return history_; }
  // The sun before anything is recorded (config/render.toml); journalled with the starting state.
  void setStartingLight(const Light& light) { scene_.light = light; }
  // Replaces the cloud (open a saved cloud); the history starts over from it. Journalled as an
  // "opened PATH" marker: a session that opens a file replays with that file where it was.
  // False with *error (the cloud unchanged) when it does not fit this session's sky.
  bool replaceVolume(const Volume& volume, int64_t t_ns, const std::string& source,
                     std::string* error);
  const PaintSessionSettings& settings() const { return settings_; }
  // The footprint of the stroke being painted, or of the next one (the screen ÷ brush size).
  int footprintWidth() const { return engine_.footprintWidth(); }
  int footprintHeight() const { return engine_.footprintHeight(); }
  float brushSize() const { return engine_.brushSize(); }
  uint32_t strokesMapped() const { return strokes_mapped_; }
  // The calibration in force (built-in defaults until setCalibration).
  const CalibrationProfile& calibration() const { return profile_; }
  // The pressure range in force (ui::SetPressureRange).
  const PressureRange& pressureRange() const { return pressure_range_; }
  const std::string& calibratorError() const { return calibrator_error_; }
  uint64_t samplesWithoutDevice() const { return samples_without_device_; }
  void setQuietMapping(bool quiet) { mapper_.setQuiet(quiet); }
  // The circles the hybrid mapping grew for the last mapped stroke (footprint pixels; empty
  // after a ray-marching stroke), for the C overlay.
  const std::vector<Circle>& lastCircles() const { return mapper_.lastCircles(); }
  BrushKind selectedBrush() const { return engine_.selectedBrush(); }
  MappingMethod mappingMethod() const { return method_; }

 private:
  struct Applier;  // apply's handler of each typed change (paint_session.cpp)
  // Parts of applyRecord: a Session record and a Settings record checked against this session.
  bool applySessionRecord(const JournalRecord& record, std::string* error);
  bool applySettingsRecord(const JournalRecord& record, std::string* error);
  void journalText(JournalRecordType type, int64_t t_ns, const std::string& text);
  void applyView();
  void mapFinishedStroke(SampleOutcome* outcome, int64_t t_ns);
  // Before an edit writes: grows the sky (up to reachableSky) to hold where the edit can write,
  // `reach_of` the sky as it is. A placement's reach depends on the sky it is placed in (its
  // anchor's fallback, its voxel grid), so it is asked again after each growth until the sky holds
  // it. True when the sky grew. The one growth path of strokes and placements.
  bool growSkyToHold(const std::function<SkyReach(const Volume&)>& reach_of);
  void syncJournal();  // fsync at a stroke's end (paint or rub-out)
  void recordStep(const SceneState& before, const std::string& label);
  void takeFrame(const WindowFrame& frame);

  PaintSessionSettings settings_;
  BrushConfig brush_config_;
  MappingConfig mapping_config_;
  std::string render_settings_;
  int footprint_w_, footprint_h_;
  SkyExtent sky_;
  int widest_span_;
  uint32_t sky_growths_ = 0, last_growth_stroke_ = 0;
  Volume volume_;
  StrokeEngine engine_;
  StrokeMapper mapper_;
  MappingMethod method_;
  CalibrationProfile profile_;
  std::optional<PenDeviceInfo> device_;
  std::unique_ptr<Calibrator> calibrator_;
  PressureRange pressure_range_;  // ui::SetPressureRange (default: the pen's whole range)
  std::string calibrator_error_;
  SceneState scene_;
  Mode mode_ = Mode::kPaint;
  EraseTool erase_tool_ = EraseTool::kRubOut;
  float vacuum_diameter_ = 0.3f, rubout_diameter_ = 0.12f;  // world units (sky box is 2 wide)
  bool rubbing_ = false;                                    // a rub-out is in progress
  bool pen_captured_ = false;
  bool menu_open_ = false;
  std::string style_ = "thesis";
  std::string opened_source_;     // the saved cloud the session started from, if any
  bool held_until_lift_ = false;  // a stroke ended by itself; the pen must lift first
  glm::vec2 still_anchor_{0.0f};  // where the pen last moved 2 px or more
  int64_t still_since_ns_ = 0, light_since_ns_ = -1;  // the on-screen UI holds the pen
  History history_;
  uint32_t strokes_mapped_ = 0;
  uint64_t samples_without_device_ = 0;
  JournalWriter* journal_ = nullptr;
  bool resuming_ = false;  // resumeRecordingTo until the first sample
  bool reproducible_record_ = false;
  SyncMarkerSender* sync_sender_ = nullptr;
  std::function<int64_t()> sync_now_ns_;  // the session clock's now; empty: none
  uint64_t sync_seq_ = 0;                 // the last sync marker's sequence number
};

}  // namespace cb
