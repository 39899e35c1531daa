#include "app/shell/operator_panel_screen.h"

#include <algorithm>
#include <cstdio>

#include "app/render/gl/gl.h"

namespace cb {
namespace {

constexpr uint32_t kEscape = 0xff1b, kBackSpace = 0xff08;
constexpr int kMaxFailures = 3;
constexpr double kLockSeconds = 60.0;
constexpr double kPinTimeoutSeconds = 20.0, kPanelTimeoutSeconds = 120.0;

uint32_t lower(uint32_t k) {
  return k >= 'A' && k <= 'Z' ? k - 'A' + 'a' : k;
}

}  // namespace

OperatorPanelScreen::OperatorPanelScreen(const Clock& clock, std::string pin, UiOverlay* ui)
    : clock_(clock), pin_(std::move(pin)), ui_(ui) {}

const char* OperatorPanelScreen::actionName(OperatorActionKind kind) {
  switch (kind) {
    case OperatorActionKind::kOpened:
      return "panel-opened";
    case OperatorActionKind::kWrongPin:
      return "wrong-pin";
    case OperatorActionKind::kLockedOut:
      return "locked-out";
    case OperatorActionKind::kClosed:
      return "panel-closed";
    case OperatorActionKind::kIdleSeconds:
      return "set-idle-seconds";
    case OperatorActionKind::kWarningSeconds:
      return "set-warning-seconds";
    case OperatorActionKind::kToggleGallery:
      return "toggle-gallery";
    case OperatorActionKind::kExportCloud:
      return "export-cloud";
    case OperatorActionKind::kCalibrate:
      return "calibrate";
    case OperatorActionKind::kCalibratePressure:
      return "calibrate-pressure";
    case OperatorActionKind::kShutdown:
      return "shutdown";
  }
  return "?";
}

void OperatorPanelScreen::askPin() {
  state_ = State::kPin;
  typed_.clear();
  last_key_ns_ = clock_.nowNs();
}

void OperatorPanelScreen::close() {
  const bool was_open = unlocked();
  state_ = State::kClosed;
  typed_.clear();
  if (was_open) actions_.push_back({OperatorActionKind::kClosed});
}

std::vector<OperatorAction> OperatorPanelScreen::takeActions() {
  std::vector<OperatorAction> out;
  out.swap(actions_);
  return out;
}

bool OperatorPanelScreen::onKey(const DisplayEvent& event, int64_t t_ns) {
  if (state_ == State::kClosed) return false;
  last_key_ns_ = t_ns;
  const uint32_t k = lower(event.keysym);
  if (k == kEscape) {
    close();
    return true;
  }
  if (state_ == State::kPin) {
    if (k == kBackSpace && !typed_.empty()) typed_.pop_back();
    if (k < '0' || k > '9') return true;  // modifiers and other keys: ignored, still taken
    if (t_ns < locked_until_ns_) return true;
    typed_ += char(k);
    if (typed_.size() < pin_.size()) return true;
    if (typed_ == pin_) {
      failures_ = 0;
      state_ = State::kPanel;
      values_.message.clear();
      actions_.push_back({OperatorActionKind::kOpened});
    } else {
      ++failures_;
      actions_.push_back({OperatorActionKind::kWrongPin, double(failures_)});
      if (failures_ >= kMaxFailures) {
        locked_until_ns_ = t_ns + int64_t(kLockSeconds * 1e9);
        failures_ = 0;
        actions_.push_back({OperatorActionKind::kLockedOut, kLockSeconds});
      }
    }
    typed_.clear();
    return true;
  }
  if (state_ == State::kConfirmShutdown) {
    if (k == 'y') {
      actions_.push_back({OperatorActionKind::kShutdown});
      close();
    } else {
      state_ = State::kPanel;
      values_.message = "shutdown cancelled";
    }
    return true;
  }
  switch (k) {
    case '1':
    case '2':
      actions_.push_back({OperatorActionKind::kIdleSeconds,
                          std::max(values_.warning_seconds + 5.0,
                                   values_.idle_seconds + (k == '1' ? -15.0 : 15.0))});
      break;
    case '3':
    case '4':
      actions_.push_back({OperatorActionKind::kWarningSeconds,
                          std::clamp(values_.warning_seconds + (k == '3' ? -5.0 : 5.0), 0.0,
                                     values_.idle_seconds - 5.0)});
      break;
    case 'g':
      actions_.push_back({OperatorActionKind::kToggleGallery});
      break;
    case 'e':
      actions_.push_back({OperatorActionKind::kExportCloud});
      break;
    case 'c':
      actions_.push_back({OperatorActionKind::kCalibrate});
      break;
    case 'p':
      actions_.push_back({OperatorActionKind::kCalibratePressure});
      break;
    case 'x':
      state_ = State::kConfirmShutdown;
      break;
    default:
      break;
  }
  return true;
}

std::string OperatorPanelScreen::update(const FrameContext& frame) {
  (void)frame;
  if (state_ == State::kClosed) return "";
  const double quiet = double(clock_.nowNs() - last_key_ns_) / 1e9;
  if (quiet >= (state_ == State::kPin ? kPinTimeoutSeconds : kPanelTimeoutSeconds)) close();
  return "";
}

bool OperatorPanelScreen::draw(FrameContext& frame, std::string* error) {
  (void)error;
  glBindFramebuffer(GL_FRAMEBUFFER, frame.display.framebuffer());
  glViewport(0, 0, frame.width, frame.height);
  glClearColor(0.06f, 0.07f, 0.09f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (!ui_) return true;
  const float w = float(frame.width), h = float(frame.height);
  const float big = std::max(20.0f, 0.05f * h), line = std::max(14.0f, 0.032f * h);
  std::vector<UiLabel> labels;
  const float x = 0.08f * w;
  float y = 0.08f * h;
  const auto add = [&](const std::string& text, float size, uint32_t rgba) {
    labels.push_back({x, y, text, size, rgba, false, 0});
    y += size * 1.45f;
  };
  add("cloudbrush kiosk - operator panel", big, 0xffd266ffu);
  if (state_ == State::kPin) {
    const bool locked = clock_.nowNs() < locked_until_ns_;
    if (locked) {
      char text[96];
      std::snprintf(text, sizeof text, "Too many wrong PINs: locked for %d s more",
                    int(double(locked_until_ns_ - clock_.nowNs()) / 1e9 + 0.999));
      add(text, line, 0xff8080ffu);
    } else {
      add("Type the PIN on the number row (" + std::to_string(pin_.size()) +
              " digits; Esc cancels):",
          line, 0xffffffffu);
      add(std::string(typed_.size(), '*') + std::string(pin_.size() - typed_.size(), '_'), big,
          0xffffffffu);
    }
    add("Waiting for the PIN. Visitors: please ask the staff.", line, 0xb8c4d0ffu);
  } else {
    char text[200];
    std::snprintf(text, sizeof text, "1 / 2   idle time  -/+ 15 s   (now %.0f s)",
                  values_.idle_seconds);
    add(text, line, 0xffffffffu);
    std::snprintf(text, sizeof text, "3 / 4   countdown  -/+ 5 s    (now %.0f s)",
                  values_.warning_seconds);
    add(text, line, 0xffffffffu);
    std::snprintf(text, sizeof text, "G       gallery on/off      (now %s, %ld entries)",
                  values_.gallery_enabled ? "on" : "off", values_.gallery_entries);
    add(text, line, 0xffffffffu);
    add("E       export the current cloud to " + values_.data_dir + "/exports", line, 0xffffffffu);
    add("C       calibrate the pen (tap the targets; Esc cancels)", line, 0xffffffffu);
    add("P       calibrate the pressure: press lightly, then firmly (now " +
            values_.pressure_range + ")",
        line, 0xffffffffu);
    add(state_ == State::kConfirmShutdown ? "X       shut down: press Y to confirm, any other key "
                                            "cancels"
                                          : "X       shut the kiosk down",
        line, state_ == State::kConfirmShutdown ? 0xff8080ffu : 0xffffffffu);
    add("Esc     close the panel (it closes by itself after 2 min)", line, 0xffffffffu);
    y += line;
    add("Every action is logged to " + values_.data_dir + "/operator.log", line, 0xb8c4d0ffu);
    if (!values_.message.empty()) add(values_.message, line, 0x9be39bffu);
  }
  ui_->drawLabels(frame.width, frame.height, labels);
  return true;
}

}  // namespace cb
