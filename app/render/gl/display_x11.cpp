// X11 platform: a window covering the whole screen, asked to be fullscreen through
// _NET_WM_STATE_FULLSCREEN (honoured by any EWMH window manager; with none, as under Xvfb, the
// window already covers the screen), an EGL window surface on it, Esc/q or closing quits.
#include "app/render/gl/display_platforms.h"

#include <EGL/eglext.h>
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>

#include <chrono>
#include <clocale>
#include <cstdlib>
#include <thread>

namespace cb {
namespace {

class X11Display final : public Display {
 public:
  ~X11Display() override {
    if (context_.display != EGL_NO_DISPLAY) {
      eglMakeCurrent(context_.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (egl_surface_ != EGL_NO_SURFACE) eglDestroySurface(context_.display, egl_surface_);
    }
    destroyGlContext(&context_);
    if (ic_) XDestroyIC(ic_);
    if (im_) XCloseIM(im_);
    if (x_) {
      if (window_) XDestroyWindow(x_, window_);
      if (colormap_) XFreeColormap(x_, colormap_);
      if (blank_cursor_) XFreeCursor(x_, blank_cursor_);
      XCloseDisplay(x_);
    }
  }

  bool open(const DisplayOptions& options, std::string* error) {
    const char* name = options.x11_display.empty() ? nullptr : options.x11_display.c_str();
    x_ = XOpenDisplay(name);
    if (!x_) {
      const char* env = std::getenv("DISPLAY");
      *error = std::string("cannot open X display '") + (name ? name : (env ? env : "")) + "'";
      return false;
    }
    where_ = std::string("X display '") + DisplayString(x_) + "'";
    const int screen = DefaultScreen(x_);
    width_ = DisplayWidth(x_, screen);
    height_ = DisplayHeight(x_, screen);

    EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_X11_KHR, x_, nullptr);
    if (display == EGL_NO_DISPLAY) {
      *error = where_ + ": no EGL display on X11 (needs EGL_KHR_platform_x11, libegl-mesa0)";
      return false;
    }
    const EGLint default_visual = EGLint(XVisualIDFromVisual(DefaultVisual(x_, screen)));
    if (!createGlContext(display, EGL_WINDOW_BIT, default_visual, &context_, error)) {
      *error = where_ + ": " + *error;
      return false;
    }
    if (!createWindow(screen, error)) return false;
    openInputMethod();
    egl_surface_ = eglCreatePlatformWindowSurface(display, context_.config, &window_, nullptr);
    if (egl_surface_ == EGL_NO_SURFACE) {
      *error = where_ + ": eglCreatePlatformWindowSurface failed (EGL error " +
               std::to_string(eglGetError()) + ")";
      return false;
    }
    if (!makeCurrent(error)) return false;
    if (!checkGlVersion(&context_, error)) {
      *error = where_ + ": " + *error;
      return false;
    }
    eglSwapInterval(display, 1);
    glViewport(0, 0, width_, height_);
    return true;
  }

  const char* platformName() const override { return "x11"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  GLuint framebuffer() const override { return 0; }

  bool makeCurrent(std::string* error) override {
    if (eglMakeCurrent(context_.display, egl_surface_, egl_surface_, context_.context)) return true;
    if (error) *error = where_ + ": eglMakeCurrent on the window failed";
    return false;
  }

  bool present(std::string* error) override {
    FrameTiming timing;
    timing.frame = timings_.total() + 1;
    timing.submit_ns = monotonicNowNs();
    if (!eglSwapBuffers(context_.display, egl_surface_)) {
      *error = where_ + ": eglSwapBuffers failed (EGL error " + std::to_string(eglGetError()) + ")";
      return false;
    }
    // No Present completion events are read: the frame counts as shown when the swap returned
    // and the GL work behind it finished (llvmpipe copies the image to the window in the swap).
    glFinish();
    timing.shown_ns = monotonicNowNs();
    timings_.push(timing);
    return true;
  }

  std::optional<double> refreshHz(std::string* why_unknown) const override {
    if (why_unknown) *why_unknown = "x11: a window; the X server's mode (RandR) is not queried";
    return std::nullopt;
  }
  std::vector<DisplayEvent> pollEvents() override {
    std::vector<DisplayEvent> events;
    while (XPending(x_)) {
      XEvent xev;
      XNextEvent(x_, &xev);
      if (XFilterEvent(&xev, None)) continue;  // the input method's (a key of a composition)
      DisplayEvent event;
      if (xev.type == KeyPress) {
        // The keysym under the server's layout and the shift level (XLookupString), so a key
        // means what its cap says on any layout; Ctrl/Alt are reported as modifiers.
        KeySym sym = NoSymbol;
        char text[8];
        XLookupString(&xev.xkey, text, sizeof text, &sym, nullptr);
        event.kind = DisplayEvent::Kind::KeyDown;
        event.keysym = uint32_t(sym);
        event.modifiers = ((xev.xkey.state & ShiftMask) ? DisplayEvent::kShift : 0u) |
                          ((xev.xkey.state & ControlMask) ? DisplayEvent::kCtrl : 0u) |
                          ((xev.xkey.state & Mod1Mask) ? DisplayEvent::kAlt : 0u);
        event.text = typedText(&xev.xkey, sym);
        events.push_back(event);
      } else if (xev.type == MotionNotify) {
        event.kind = DisplayEvent::Kind::PointerMove;
        event.x = float(xev.xmotion.x);
        event.y = float(xev.xmotion.y);
        events.push_back(event);
      } else if ((xev.type == ButtonPress && xev.xbutton.button <= 5) ||
                 (xev.type == ButtonRelease && xev.xbutton.button <= 3)) {
        event.kind = xev.type == ButtonPress ? DisplayEvent::Kind::PointerDown
                                             : DisplayEvent::Kind::PointerUp;
        event.x = float(xev.xbutton.x);
        event.y = float(xev.xbutton.y);
        event.button = int(xev.xbutton.button);
        events.push_back(event);
      } else if (xev.type == ClientMessage && Atom(xev.xclient.data.l[0]) == wm_delete_window_) {
        event.kind = DisplayEvent::Kind::Quit;
        events.push_back(event);
      } else if (xev.type == ConfigureNotify &&
                 (xev.xconfigure.width != width_ || xev.xconfigure.height != height_)) {
        width_ = xev.xconfigure.width;
        height_ = xev.xconfigure.height;
        event.kind = DisplayEvent::Kind::Resize;
        event.width = width_;
        event.height = height_;
        events.push_back(event);
      }
    }
    return events;
  }

 private:
  // Typed text in any script: the X input method (XIM; an IME such as fcitx or ibus composes
  // Chinese through it) hands over UTF-8 via Xutf8LookupString. Without one, the keysym's
  // character. Keys still work when neither opens.
  void openInputMethod() {
    std::setlocale(LC_CTYPE, "");  // Xlib's input methods follow the locale's character type
    XSetLocaleModifiers("");
    im_ = XOpenIM(x_, nullptr, nullptr, nullptr);
    if (!im_) {
      XSetLocaleModifiers("@im=none");  // no IME running: Xlib's own (dead keys, compose)
      im_ = XOpenIM(x_, nullptr, nullptr, nullptr);
    }
    if (!im_) return;
    ic_ = XCreateIC(im_, XNInputStyle, XIMPreeditNothing | XIMStatusNothing, XNClientWindow,
                    window_, XNFocusWindow, window_, nullptr);
    if (ic_) XSetICFocus(ic_);
  }

  std::string typedText(XKeyEvent* key, KeySym sym) {
    if (ic_) {
      char buffer[256];
      Status status = 0;
      const int n = Xutf8LookupString(ic_, key, buffer, sizeof buffer, nullptr, &status);
      if ((status == XLookupChars || status == XLookupBoth) && n > 0)
        return std::string(buffer, size_t(n));
      if (status != XBufferOverflow) return "";
    }
    return keysymText(sym);
  }

  // The character of a Latin-1 or Unicode keysym (X11 keysymdef.h: 0x20..0xff are Latin-1,
  // 0x1000000 + U is code point U), as UTF-8; "" for function keys.
  static std::string keysymText(KeySym sym) {
    uint32_t c = 0;
    if ((sym >= 0x20 && sym <= 0x7e) || (sym >= 0xa0 && sym <= 0xff))
      c = uint32_t(sym);
    else if (sym >= 0x1000100 && sym <= 0x110ffff)
      c = uint32_t(sym - 0x1000000);
    else
      return "";
    std::string out;
    if (c < 0x80) {
      out += char(c);
    } else if (c < 0x800) {
      out += char(0xc0 | (c >> 6));
      out += char(0x80 | (c & 0x3f));
    } else if (c < 0x10000) {
      out += char(0xe0 | (c >> 12));
      out += char(0x80 | ((c >> 6) & 0x3f));
      out += char(0x80 | (c & 0x3f));
    } else {
      out += char(0xf0 | (c >> 18));
      out += char(0x80 | ((c >> 12) & 0x3f));
      out += char(0x80 | ((c >> 6) & 0x3f));
      out += char(0x80 | (c & 0x3f));
    }
    return out;
  }

  bool createWindow(int screen, std::string* error) {
    EGLint visual_id = 0;
    eglGetConfigAttrib(context_.display, context_.config, EGL_NATIVE_VISUAL_ID, &visual_id);
    XVisualInfo templ{};
    templ.visualid = VisualID(visual_id);
    int count = 0;
    XVisualInfo* visual = XGetVisualInfo(x_, VisualIDMask, &templ, &count);
    if (!visual || count == 0) {
      *error = where_ + ": the EGL config's X visual " + std::to_string(visual_id) + " is missing";
      return false;
    }
    const Window root = RootWindow(x_, screen);
    colormap_ = XCreateColormap(x_, root, visual->visual, AllocNone);
    XSetWindowAttributes attributes{};
    attributes.colormap = colormap_;
    attributes.background_pixel = BlackPixel(x_, screen);
    attributes.border_pixel = 0;
    attributes.event_mask = KeyPressMask | KeyReleaseMask | FocusChangeMask | StructureNotifyMask |
                            ExposureMask | PointerMotionMask | ButtonPressMask | ButtonReleaseMask;
    window_ = XCreateWindow(x_, root, 0, 0, unsigned(width_), unsigned(height_), 0, visual->depth,
                            InputOutput, visual->visual,
                            CWColormap | CWBackPixel | CWBorderPixel | CWEventMask, &attributes);
    XFree(visual);
    XStoreName(x_, window_, "cloudbrush");
    wm_delete_window_ = XInternAtom(x_, "WM_DELETE_WINDOW", False);
    XSetWMProtocols(x_, window_, &wm_delete_window_, 1);
    hideCursor();
    // EWMH fullscreen: as a property before mapping (the window manager reads it on map) ...
    const Atom wm_state = XInternAtom(x_, "_NET_WM_STATE", False);
    const Atom fullscreen = XInternAtom(x_, "_NET_WM_STATE_FULLSCREEN", False);
    XChangeProperty(x_, window_, wm_state, XA_ATOM, 32, PropModeReplace,
                    reinterpret_cast<const unsigned char*>(&fullscreen), 1);
    XMapRaised(x_, window_);
    // ... and as a client message after, for managers that only react to requests.
    XEvent request{};
    request.xclient.type = ClientMessage;
    request.xclient.window = window_;
    request.xclient.message_type = wm_state;
    request.xclient.format = 32;
    request.xclient.data.l[0] = 1;  // _NET_WM_STATE_ADD
    request.xclient.data.l[1] = long(fullscreen);
    request.xclient.data.l[3] = 1;  // source: normal application
    XSendEvent(x_, root, False, SubstructureRedirectMask | SubstructureNotifyMask, &request);
    return waitForMap(error);
  }

  // The window must be viewable before the first frame, or the frame is lost.
  bool waitForMap(std::string* error) {
    for (int i = 0; i < 500; ++i) {
      XEvent xev;
      if (XCheckTypedWindowEvent(x_, window_, MapNotify, &xev)) return true;
      XFlush(x_);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    *error = where_ + ": the fullscreen window was not mapped within 5 s";
    return false;
  }

  // A kiosk shows no pointer: an empty 1x1 cursor.
  void hideCursor() {
    static const char empty[1] = {0};
    const Pixmap pixmap = XCreateBitmapFromData(x_, window_, empty, 1, 1);
    XColor black{};
    blank_cursor_ = XCreatePixmapCursor(x_, pixmap, pixmap, &black, &black, 0, 0);
    XDefineCursor(x_, window_, blank_cursor_);
    XFreePixmap(x_, pixmap);
  }

  ::Display* x_ = nullptr;
  Window window_ = 0;
  Colormap colormap_ = 0;
  Cursor blank_cursor_ = 0;
  Atom wm_delete_window_ = 0;
  XIM im_ = nullptr;
  XIC ic_ = nullptr;
  EGLSurface egl_surface_ = EGL_NO_SURFACE;
  std::string where_;
  int width_ = 0, height_ = 0;
};

}  // namespace

std::unique_ptr<Display> openX11Display(const DisplayOptions& options, std::string* error) {
  auto display = std::make_unique<X11Display>();
  if (!display->open(options, error)) return nullptr;
  return display;
}

}  // namespace cb
