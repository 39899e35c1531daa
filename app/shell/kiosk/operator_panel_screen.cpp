#include "app/shell/kiosk/operator_panel_screen.h"

#include <algorithm>
#include <cstdio>

#include "app/render/gl/gl.h"

namespace cb {
namespace {

constexpr uint32_t kEscape = 0xff1b, kBackSpace = 0xff08, kReturn = 0xff0d, kKpEnter = 0xff8d;
constexpr double kPinTimeoutSeconds = 20.0, kPanelTimeoutSeconds = 120.0;

uint32_t lower(uint32_t k) {
  return k >= 'A' && k <= 'Z' ? k - 'A' + 'a' : k;
}

}  // namespace

OperatorPanelScreen::OperatorPanelScreen(const Clock& clock, OperatorPinGuard* pin, UiOverlay* ui)
    : clock_(clock), pin_(pin), ui_(ui) {}

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
    case OperatorActionKind::kPinSet:
      return "pin-set";
  }
  return "?";
}

void OperatorPanelScreen::askPin() {
  state_ = pin_->hasPin() ? State::kPin : State::kNewPin;
  typed_.clear();
  last_key_ns_ = clock_.nowNs();
}

void OperatorPanelScreen::close() {
  const bool was_open = unlocked();
  state_ = State::kClosed;
  typed_.clear();
  if (was_open) actions_.push_back({OperatorActionKind::kClosed});
}

void OperatorPanelScreen::onPinKey(uint32_t k) {
  if (k == kBackSpace && !typed_.empty()) typed_.pop_back();
  const bool enter = k == kReturn || k == kKpEnter;
  if (state_ != State::kPin && enter) return onNewPinEntered();
  if (state_ == State::kPin && pin_->lockedForSeconds() > 0.0) return;
  if (!enter) {
    // Digits only, at most 12 (other keys: ignored, still taken). Entry ends with Enter, not
    // at a stored length, so the prompt says nothing of the PIN's length.
    if (k >= '0' && k <= '9' && typed_.size() < 12) typed_ += char(k);
    return;
  }
  if (typed_.empty()) return;  // Enter alone is no try
  switch (pin_->check(typed_)) {
    case OperatorPinGuard::Result::kRight:
      state_ = State::kPanel;
      values_.message.clear();
      actions_.push_back({OperatorActionKind::kOpened});
      break;
    case OperatorPinGuard::Result::kWrong:
      actions_.push_back({OperatorActionKind::kWrongPin, double(pin_->failures())});
      break;
    case OperatorPinGuard::Result::kLockedNow:
      actions_.push_back({OperatorActionKind::kWrongPin, double(pin_->failures())});
      actions_.push_back({OperatorActionKind::kLockedOut, pin_->lastLockSeconds()});
      break;
    case OperatorPinGuard::Result::kStillLocked:
      break;
  }
  typed_.clear();
}

void OperatorPanelScreen::onNewPinEntered() {
  // First start: no PIN yet. Typed twice, then hashed into the data dir (operator_pin.h).
  if (state_ == State::kNewPin) {
    pin_message_ = operatorPinProblem(typed_);
    if (pin_message_.empty()) {
      new_pin_ = typed_;
      state_ = State::kConfirmNewPin;
    }
  } else if (typed_ != new_pin_) {
    pin_message_ = "the two PINs differ: type the new PIN again";
    state_ = State::kNewPin;
  } else if (std::string error; !pin_->setPin(new_pin_, &error)) {
    pin_message_ = "the PIN was NOT SAVED: " + error;
    state_ = State::kNewPin;
  } else {
    pin_message_.clear();
    state_ = State::kPanel;
    values_.message = "the operator PIN is set (" + std::to_string(new_pin_.size()) + " digits)";
    actions_.push_back({OperatorActionKind::kPinSet});
    actions_.push_back({OperatorActionKind::kOpened});
  }
  if (state_ != State::kConfirmNewPin) {
    std::fill(new_pin_.begin(), new_pin_.end(), '\0');
    new_pin_.clear();
  }
  typed_.clear();
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
  if (state_ == State::kPin || state_ == State::kNewPin || state_ == State::kConfirmNewPin) {
    onPinKey(k);
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

namespace {

// `text` cut at spaces into lines of at most `max_chars` (a word longer than that stays whole).
std::vector<std::string> wrapWords(const std::string& text, size_t max_chars) {
  std::vector<std::string> lines(1);
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find(' ', at);
    end = end == std::string::npos ? text.size() : end;
    const std::string word = text.substr(at, end - at);
    if (!lines.back().empty() && lines.back().size() + 1 + word.size() > max_chars)
      lines.emplace_back();
    lines.back() += (lines.back().empty() ? "" : " ") + word;
    at = end + 1;
  }
  return lines;
}

}  // namespace

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
  if (state_ == State::kNewPin || state_ == State::kConfirmNewPin) {
    add(state_ == State::kNewPin
            ? "No operator PIN is set yet. Type a new PIN (4 to 12 digits), then Enter:"
            : "Type the new PIN again, then Enter:",
        line, 0xffffffffu);
    add(std::string(typed_.size(), '*') + "_", big, 0xffffffffu);
    if (!pin_message_.empty()) add(pin_message_, line, 0xff8080ffu);
    add("It is stored hashed in the data dir; Esc cancels.", line, 0xb8c4d0ffu);
  } else if (state_ == State::kPin) {
    const double locked_s = pin_->lockedForSeconds();
    if (locked_s > 0.0) {
      char text[96];
      std::snprintf(text, sizeof text, "Too many wrong PINs: locked for %d s more",
                    int(locked_s + 0.999));
      add(text, line, 0xff8080ffu);
    } else {
      add("Type the PIN on the number row, then Enter (Esc cancels):", line, 0xffffffffu);
      add(std::string(typed_.size(), '*') + "_", big, 0xffffffffu);
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
    // The disk line names the data dir and the figures: wrapped to the screen (glyphs are taken
    // as half the text size wide, more than this font's average).
    const size_t max_chars = size_t(std::max(20.0f, 0.84f * w / (0.5f * line)));
    if (!values_.storage.empty())
      for (const std::string& part : wrapWords("Disk: " + values_.storage, max_chars))
        add(part, line, values_.storage_ok ? 0xb8c4d0ffu : 0xff8080ffu);
    // What was lost, not only that saving is off: the same count as health.json's saves_failed.
    for (const std::string& part :
         wrapWords("Not saved since the start: " + std::to_string(values_.saves_failed) +
                       " (visitors' clouds and journals that could not be written; " +
                       std::to_string(values_.gallery_saved) +
                       (values_.gallery_saved == 1 ? " cloud saved)" : " clouds saved)"),
                   max_chars))
      add(part, line, values_.saves_failed == 0 ? 0xb8c4d0ffu : 0xff8080ffu);
    if (!values_.message.empty()) add(values_.message, line, 0x9be39bffu);
  }
  labels_ = labels;
  ui_->drawLabels(frame.width, frame.height, labels);
  return true;
}

}  // namespace cb
