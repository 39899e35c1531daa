// The exhibition kiosk's screen: what `cloudbrush kiosk` runs in the shell's one frame
// loop. It holds the painter (paint_screen.h, in visitor mode) and the kiosk's own screens and
// routes input and frames to the one active:
//
//   attract   (attract_screen.h) a bundled journal replays with the camera orbiting and the
//             invitation; the first pen proximity, mouse or key hands control to the visitor at
//             once, on an empty canvas (a fresh session and journal per visitor)
//   visitor   the painter: painting, erasing, camera, undo, "start again"; after
//             idle_seconds without input a countdown of warning_seconds, then the cloud is kept
//             in the gallery (when on), the visit ends and the attract loop resumes
//   reconnect (reconnect_screen.h) the tablet went away mid-visit; back to painting on replug,
//             with the pen's first sample (or a second after the replug without one)
//   operator  (operator_panel_screen.h) the configured key combination, then the PIN; every
//             action is logged to <data dir>/operator.log
//   calibrate the operator pressed C: the calibration flow (calibrate_flow_screen.h) takes
//             every input; Esc cancels it. The profile is saved under the data dir (where the
//             kiosk's painter looks it up), the visitor's pen uses it at once, the result is
//             logged and shown on the panel again. P runs the flow's press calibration instead
//             (press lightly, then firmly): the pressure range is saved as
//             <data dir>/pressure_range.toml (read again when the kiosk starts), the current
//             visitor's session takes it (journalled) and so does every later visitor's
//
// Visitor texts come from config/kiosk/texts.toml in the configured language. Everything the
// kiosk writes goes under the data dir: sessions/ (journals, deleted after [journals] keep_days),
// gallery/, exports/, operator.log, profiles/ and calibration-<time>.cbj. Every timer reads the
// injected Clock.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/kiosk/gallery_store.h"
#include "app/kiosk/health_status.h"
#include "app/kiosk/kiosk_config.h"
#include "app/kiosk/kiosk_texts.h"
#include "app/kiosk/operator_log.h"
#include "app/shell/calibrate/calibrate_flow_screen.h"
#include "app/shell/kiosk/attract_screen.h"
#include "app/shell/kiosk/operator_panel_screen.h"
#include "app/shell/kiosk/reconnect_screen.h"
#include "app/shell/painter/paint_screen.h"
#include "app/shell/ui_overlay.h"

namespace cb {

struct KioskSetup {
  KioskConfig config;
  KioskTexts texts;
  std::string data_dir;    // created if missing
  std::string config_dir;  // shipped defaults (config/calibration.toml for the calibration)
  std::vector<JournalRecord> attract_journal;  // may be empty (the empty sky orbits)
  PaintSessionSettings visitor_settings;
  BrushConfig brush;
  MappingConfig mapping;
  Light light;
  std::string style = "thesis";
  RenderOptions render;
  std::string render_settings;  // render.toml in force as text, journalled (formatRenderConfig)
  float moving_scale = 0.5f;    // the attract orbit's resolution scale
  bool record_journals = true;
  // Told about state changes ("attract: waiting for visitors", ...) and input (health file).
  std::function<void(const std::string& status)> on_status;
  std::function<void()> on_input;
  // Every failure to save (a gallery entry, a journal), with its reason: health.json's
  // last_error. (The kiosk logs it itself.)
  std::function<void(const std::string& problem)> on_problem;
  // The data dir's storage state changed: "" when saving works (again), else what is not saved
  // and why (health.json's "storage", the metrics).
  std::function<void(const std::string& storage_problem)> on_storage;
};

// The exit status of `cloudbrush kiosk` after the operator shut it down (the unit's
// RestartPreventExitStatus=, so systemd does not start it again).
inline constexpr int kOperatorShutdownExitStatus = 10;

class KioskScreen : public Screen {
 public:
  enum class State { kAttract, kVisitor, kReconnect, kOperator, kCalibrate };

  // `paint` runs in visitor mode with `pen` attached; the kiosk attaches its visitor sessions.
  // None owned.
  KioskScreen(Display& display, VolumeRenderer& renderer, PaintScreen& paint, PenSource* pen,
              const Clock& clock, KioskSetup setup);
  ~KioskScreen() override;

  const char* name() const override { return "kiosk"; }
  void onPenSamples(const std::vector<PenSample>& samples) override;
  void onCommand(Command command, int64_t t_ns) override;
  bool onKey(const DisplayEvent& event, int64_t t_ns) override;
  void onPointer(const DisplayEvent& event) override;
  void onResize(int width, int height) override;
  std::string update(const FrameContext& frame) override;
  bool needsFrame() const override;
  bool draw(FrameContext& frame, std::string* error) override;
  void presented(const FrameContext& frame, double frame_ms) override;
  bool allowsQuit() const override { return false; }

  // The visitor is about to clear their cloud ("start again"): keep it in the gallery (when on).
  // PaintLoopOptions::before_start_again calls this.
  void keepFinishedCloud(const std::string& why);
  // The kiosk is being stopped (SIGTERM from systemd): the current visitor's cloud, if any, goes
  // to the gallery (when on) and their journal is closed.
  void stopping();

  State state() const { return state_; }
  static const char* stateName(State state);
  long idleResets() const { return idle_resets_; }
  long visits() const { return visits_; }
  // After an idle reset: the next visitor's fresh session is made (the finished one freed).
  bool nextVisitorReady() const { return visitor_ && !next_visitor_pending_; }
  // The current visitor's session; between visits, the fresh one the next visitor gets (made
  // just after the attract loop's first frame following a reset; until then the last one's).
  const PaintSession* visitorSession() const { return visitor_.get(); }
  const AttractScreen& attract() const { return attract_; }
  const OperatorPanelScreen& operatorPanel() const { return panel_; }
  const OperatorPinGuard& operatorPin() const { return pin_guard_; }
  // The operator's calibration while the state is kCalibrate, else null.
  const CalibrateFlowScreen* calibration() const { return calibration_.get(); }
  // The pressure range the operator's press calibration set (null: the pen's whole range).
  const std::optional<PressureRange>& pressureRange() const { return pressure_range_; }
  const KioskConfig& config() const { return setup_.config; }
  // The countdown (or "saved as number N") shown over the painter, or "".
  const std::string& notice() const { return notice_; }
  const std::vector<long>& gallerySaved() const { return gallery_saved_; }
  // Gallery entries and journals that could not be written (disk full, I/O error).
  long savesFailed() const { return saves_failed_; }
  // Strokes mapped by every visitor so far.
  long strokes() const { return strokes_done_ + (visitor_ ? long(visitor_->strokesMapped()) : 0); }
  // For the health file and the metrics.
  KioskCounts counts() const;
  // "" while saving works; else what is not saved and why (also on the operator panel).
  const std::string& storageProblem() const { return storage_problem_; }

 private:
  void setState(State state);
  void prepareVisitor();
  void beginVisit(int64_t now);
  void endVisit(int64_t now, const std::string& why);
  void input(int64_t now);
  void cleanUpOldData();
  // The kiosk clock's time as a file time: the wall time at start plus the clock's time since.
  // Journals and gallery entries carry it and retention (keep_days) is judged at it, so the
  // injected clock (a simulated month) ages files as it runs; on the real clock it is the wall
  // clock's time.
  std::filesystem::file_time_type fileTimeNow() const;
  // Storage (the floor of free space, gallery.min_free_mb): the oldest gallery entries go until
  // `need_bytes` more than the floor are free; false with *why when even then they are not.
  bool roomToWrite(uint64_t need_bytes, std::string* why);
  void reportProblem(const std::string& problem);
  void setStorageProblem(const std::string& problem);
  void checkStorage(int64_t now);
  void openJournal(int64_t now);
  void closeJournal();
  // At start: the cloud of a visit the kiosk was killed in (app/kiosk/unsaved_visit.h), replayed
  // from its journal into the gallery, once.
  void recoverUnsavedVisit();
  std::string storageSummary();
  void runOperatorActions(int64_t now);
  void logOperator(const std::string& action);
  void startCalibration(int64_t now, bool pressure);
  void finishCalibration(int64_t now);
  void updateTexts();
  bool visiting() const { return state_ == State::kVisitor || state_ == State::kReconnect; }

  Display& display_;
  VolumeRenderer& renderer_;
  PaintScreen& paint_;
  PenSource* pen_;
  const Clock& clock_;
  KioskSetup setup_;
  std::string session_dir_;
  UiOverlay ui_;
  bool ui_ready_ = false, ui_failed_ = false;
  AttractScreen attract_;
  ReconnectScreen reconnect_;
  OperatorPinGuard pin_guard_;
  OperatorPanelScreen panel_;
  DisplayEvent operator_keys_;
  GalleryStore gallery_;
  OperatorLog operator_log_;
  int64_t clock_start_ns_;
  std::filesystem::file_time_type file_time_start_;
  State state_ = State::kAttract, before_operator_ = State::kAttract;
  std::unique_ptr<JournalWriter> journal_;
  std::unique_ptr<PaintSession> visitor_;
  std::unique_ptr<CalibrateFlowScreen> calibration_;
  std::unique_ptr<JournalWriter> calibration_record_;
  bool calibrating_pressure_ = false;
  std::optional<PressureRange> pressure_range_;  // the operator's, for every visitor
  int64_t last_input_ns_ = 0;
  int64_t saved_notice_until_ns_ = 0;
  std::string saved_notice_;
  int last_connection_ = -1;
  // The pen status the "reconnect the pen" screen last drew (none: not drawn since shown).
  std::optional<std::string> reconnect_drawn_;
  int64_t reconnected_ns_ = -1;  // the tablet came back while "reconnect the pen" showed
  static constexpr double kReconnectWaitForSampleS = 1.0;
  bool awaiting_first_sample_ = false;       // the pen (re)connected; its first sample not yet seen
  bool first_sample_frame_pending_ = false;  // that sample came; the next frame not yet presented
  bool next_visitor_pending_ = false;        // after an idle reset, until prepareVisitor() ran
  bool attract_shown_ = false;               // an attract frame was presented since the reset
  long idle_resets_ = 0, visits_ = 0;
  std::string notice_, quit_, message_;
  std::vector<long> gallery_saved_;
  long saves_failed_ = 0, strokes_done_ = 0;
  std::string storage_problem_;
  int64_t storage_checked_ns_ = 0;
  bool journal_failed_ = false;  // the visitor's journal stopped on a write error (reported)
  static constexpr double kStorageCheckS = 10.0;  // how often a full disk is looked at again
};

}  // namespace cb
