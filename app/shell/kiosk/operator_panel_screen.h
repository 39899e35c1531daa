// The kiosk's operator panel. It opens only with the key combination set in
// config/kiosk.toml ([operator] keys, e.g. Ctrl+Alt+O) followed by the PIN's digits and Enter,
// typed on the keyboard (operator_pin.h: stored hashed, no default — the first time, the panel asks
// for a new PIN twice; the third wrong PIN in a row locks it for a minute, each further one twice
// as long, kept across restarts). Open, it lists what the operator may do, each on one key:
//   1 / 2  idle time −/+ 15 s       3 / 4  warning time −/+ 5 s
//   G      gallery on/off           E      export the current cloud
//   C      calibrate the pen (the kiosk runs the calibration screens, then shows the panel again)
//   P      calibrate the pressure: press lightly, then firmly (the same way; every visitor's
//          pen then uses that range)
//   X then Y  shut the kiosk down
//   Esc    close (also after 2 min without a key)
// The panel only asks; the kiosk screen carries the actions out and logs every one of them
// (operator_log.h). Visitors never see it: the pen does nothing while it is open.
#pragma once

#include <string>
#include <vector>

#include "app/kiosk/operator_pin.h"
#include "app/shell/screen.h"
#include "app/shell/ui_overlay.h"
#include "drivers/core/clock.h"

namespace cb {

enum class OperatorActionKind {
  kOpened,       // the PIN was right
  kWrongPin,     // value: failures in a row
  kLockedOut,    // too many wrong PINs
  kClosed,       // Esc, timeout or after shutdown
  kIdleSeconds,  // value: the new idle time
  kWarningSeconds,
  kToggleGallery,
  kExportCloud,
  kCalibrate,
  kCalibratePressure,
  kShutdown,
  kPinSet,  // the first PIN was set at the kiosk
};

struct OperatorAction {
  OperatorActionKind kind;
  double value = 0.0;
};

// What the panel shows of the kiosk's settings.
struct OperatorPanelValues {
  double idle_seconds = 90.0, warning_seconds = 10.0;
  bool gallery_enabled = false;
  long gallery_entries = 0;
  std::string data_dir;
  std::string pressure_range = "the pen's whole range";  // in force for visitors
  std::string message;                                   // the result of the last action
  // The data dir's disk: "ok: N MB free" or what cannot be saved ("NOT SAVING: ..."), shown
  // in red when `storage_ok` is false.
  std::string storage;
  bool storage_ok = true;
  // Since the kiosk started (the counts health.json and the metrics carry, KioskCounts):
  // visitors' clouds kept in the gallery, and gallery entries and journals not written.
  long gallery_saved = 0, saves_failed = 0;
};

class OperatorPanelScreen : public Screen {
 public:
  // `pin` (not owned) checks the PIN, keeps the lockout and sets the first PIN.
  OperatorPanelScreen(const Clock& clock, OperatorPinGuard* pin, UiOverlay* ui);
  const char* name() const override { return "operator"; }
  void onCommand(Command, int64_t) override {}
  // Every key while the panel (or its PIN prompt) is open; always taken.
  bool onKey(const DisplayEvent& event, int64_t t_ns) override;
  std::string update(const FrameContext& frame) override;
  bool draw(FrameContext& frame, std::string* error) override;

  // The combination was typed: ask for the PIN.
  void askPin();
  bool isOpen() const { return state_ != State::kClosed; }
  bool unlocked() const { return state_ == State::kPanel || state_ == State::kConfirmShutdown; }
  // Shown again after something that took a while (the calibration): its 2 min start anew.
  void shownAgain(int64_t t_ns) { last_key_ns_ = t_ns; }
  void setValues(const OperatorPanelValues& values) { values_ = values; }
  // What the panel shows (the kiosk sets it every frame while the panel is open).
  const OperatorPanelValues& values() const { return values_; }
  // The text drawn last, line by line (tests and logs).
  const std::vector<UiLabel>& labels() const { return labels_; }
  // Actions since the last call, in order.
  std::vector<OperatorAction> takeActions();
  static const char* actionName(OperatorActionKind kind);

 private:
  enum class State { kClosed, kPin, kNewPin, kConfirmNewPin, kPanel, kConfirmShutdown };
  void close();
  void onPinKey(uint32_t keysym);
  void onNewPinEntered();
  const Clock& clock_;
  OperatorPinGuard* pin_;
  std::string new_pin_, pin_message_;
  UiOverlay* ui_;
  State state_ = State::kClosed;
  std::string typed_;
  int64_t last_key_ns_ = 0;
  OperatorPanelValues values_;
  std::vector<UiLabel> labels_;
  std::vector<OperatorAction> actions_;
};

}  // namespace cb
