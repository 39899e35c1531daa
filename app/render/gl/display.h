// One EGL display layer, three platforms (kmscube style: one small file per concern):
//   display_surfaceless.cpp  headless, renders into an offscreen framebuffer object
//   display_kms.cpp          GBM/KMS fullscreen on a DRM connector, no compositor (kiosk path)
//   display_x11.cpp          a fullscreen X11 window (desktop, Xvfb)
// openDisplay() picks one automatically (KMS if it can take the display, else X11 if DISPLAY is
// set, else surfaceless) unless DisplayOptions names one. Callers see only this interface; no
// platform header leaks out of app/render/gl.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/render/gl/display_frame_timing.h"
#include "app/render/gl/egl_context.h"
#include "app/render/gl/gl.h"

namespace cb {

enum class DisplayPlatform { Auto, Kms, X11, Surfaceless };

// "auto", "kms", "x11", "surfaceless".
const char* displayPlatformName(DisplayPlatform platform);
// Parses a --display value; false for anything else.
bool parseDisplayPlatform(std::string_view text, DisplayPlatform* out);

struct DisplayOptions {
  DisplayPlatform platform = DisplayPlatform::Auto;
  // Framebuffer size of the surfaceless platform (KMS uses the connector's preferred mode, X11
  // the screen size).
  int width = 1280;
  int height = 720;
  // DRM card for KMS; empty = the first /dev/dri/card* with a connected connector.
  std::string drm_device;
  // X11 display name; empty = $DISPLAY.
  std::string x11_display;
  // KMS, the kiosk: the terminal on stdin takes no keys and refuses VT switches while the
  // display is open (display_kms_vt.h); said on stderr when stdin is not a VT.
  bool lock_vt = false;
};

// What a display reports between frames. Keys are reported, not interpreted: `keysym` is the
// XKB keysym of the key under the active layout (the same numbers X11 uses, see
// <xkbcommon/xkbcommon-keysyms.h>), `modifiers` the modifier keys held; the UI decides what a key
// means (app/shell/keymap.h). Pointer events come from a mouse where the platform has one (X11),
// in framebuffer pixels. Quit is a window close (WM_DELETE_WINDOW) or a terminal request.
struct DisplayEvent {
  enum class Kind { Quit, KeyDown, Resize, PointerMove, PointerDown, PointerUp };
  enum Modifier : uint32_t { kShift = 1, kCtrl = 2, kAlt = 4 };
  Kind kind = Kind::Quit;
  uint32_t keysym = 0;     // KeyDown
  uint32_t modifiers = 0;  // KeyDown: Modifier bits
  int width = 0;           // Resize: the new size
  int height = 0;
  float x = 0.0f, y = 0.0f;  // Pointer*: position, y down
  int button = 0;            // PointerDown/Up: 1 left, 2 middle, 3 right; PointerDown 4/5 a wheel
                             // click away from / towards the user (X11 buttons 4, 5)
  // KeyDown: the text the key typed, UTF-8 (an input method's composed text included: X11's
  // XIM gives what an IME such as fcitx or ibus composed, e.g. Chinese), or empty.
  std::string text;

  static DisplayEvent key(uint32_t keysym, uint32_t modifiers = 0) {
    DisplayEvent event;
    event.kind = Kind::KeyDown;
    event.keysym = keysym;
    event.modifiers = modifiers;
    return event;
  }
  // A pointer event at (x, y), framebuffer pixels, y down; button 1 is the left.
  static DisplayEvent pointer(Kind kind, float x, float y, int button = 1) {
    DisplayEvent event;
    event.kind = kind;
    event.x = x;
    event.y = y;
    event.button = button;
    return event;
  }
};

class Display {
 public:
  virtual ~Display() = default;
  Display(const Display&) = delete;
  Display& operator=(const Display&) = delete;

  // "surfaceless", "kms" or "x11".
  virtual const char* platformName() const = 0;
  // Drawable size in pixels.
  virtual int width() const = 0;
  virtual int height() const = 0;
  // Makes the GL context (and surface) current on the calling thread.
  virtual bool makeCurrent(std::string* error) = 0;
  // The framebuffer to draw a frame into: 0 (the window surface) on KMS and X11, the offscreen
  // FBO on surfaceless.
  virtual GLuint framebuffer() const = 0;
  // Shows the frame drawn into framebuffer(): swap buffers, and on KMS the page flip (this
  // waits for the previous flip's event, so frames are paced by vblank). Records a FrameTiming.
  virtual bool present(std::string* error) = 0;
  // Input and window events since the last call (never blocks).
  virtual std::vector<DisplayEvent> pollEvents() = 0;
  // True where no window system delivers keys (KMS): the caller reads the keyboards itself,
  // through evdev (drivers/keyboard; the shell's FrameLoop does), and pollEvents() has none.
  virtual bool needsEvdevKeyboard() const { return false; }
  // The refresh rate the display's mode runs at (KMS: the mode's pixel clock over its total
  // size), or nullopt with *why_unknown saying why there is none to report (an offscreen
  // buffer has no refresh; the X11 window does not query the server's mode).
  virtual std::optional<double> refreshHz(std::string* why_unknown) const = 0;
  // Tests and scripted runs: queues `event` for the next pollEvents() of the surfaceless display
  // (the platform without a keyboard; KMS and X11 ignore the queue).
  void injectEvent(const DisplayEvent& event) { injected_.push_back(event); }
  // Reads the frame drawn so far (call before present()) as RGBA8, row 0 at the top.
  bool readPixels(std::vector<uint8_t>* rgba) const;

  const EglContext& context() const { return context_; }
  // Timing of the most recent presents; KMS entries carry the kernel's vblank timestamp and
  // sequence number from the page-flip event.
  const FrameTimingRing& frameTimings() const { return timings_; }

 protected:
  Display() = default;
  EglContext context_;
  FrameTimingRing timings_;
  std::vector<DisplayEvent> injected_;  // injectEvent() queue, drained by the surfaceless display
};

// Opens the display `options` asks for (or the automatic choice). On failure returns null and
// says what failed and where (device, DISPLAY name, GL version found vs. needed). With the
// automatic choice, `choice_note` (if given) says why the platforms before the chosen one were
// passed over, e.g. "kms: /dev/dri/card0: not DRM master (a compositor holds it)".
std::unique_ptr<Display> openDisplay(const DisplayOptions& options, std::string* error,
                                     std::string* choice_note = nullptr);

}  // namespace cb
