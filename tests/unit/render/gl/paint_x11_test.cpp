// The main job on a display, as the real binary under a test-started Xvfb: `cloudbrush` opens
// fullscreen on X11 by itself (DISPLAY set, no card to take), shows the paintable sky, paints
// a cloud where the mouse drags, and quits on Esc (asking first: the stroke is unsaved) with
// status 0.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "xvfb_server.h"

// After gtest: Xlib's macros (None, Bool, ...) would break its headers.
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>

#include "x11_window.h"

namespace cb {
namespace {

constexpr int kW = 320, kH = 200;

// The screen's colours: the red of the middle row at x and of a corner, the corner's blue.
struct Look {
  int centre_r = 0, corner_r = 0, corner_b = 0;
  bool sky() const { return corner_b > corner_r + 30; }
};

// A second client of the test's X server: looks at the screen, and sends the painter's window
// keys and mouse events as a person's would arrive.
class Observer {
 public:
  explicit Observer(const std::string& server) : x_(XOpenDisplay(server.c_str())) {}
  ~Observer() {
    if (x_) XCloseDisplay(x_);
  }
  bool open() const { return x_ != nullptr; }
  ::Display* display() const { return x_; }
  void use(Window window) { window_ = window; }

  Look look(int x) const {
    Look l;
    XImage* image = XGetImage(x_, DefaultRootWindow(x_), 0, 0, kW, kH, AllPlanes, ZPixmap);
    if (!image) return l;
    auto channel = [&](int px, int py, unsigned long mask) {
      const unsigned long p = XGetPixel(image, px, py) & mask;
      return int(p / (mask & ~(mask << 1)));  // shift the masked bits down to 0..255
    };
    l.centre_r = channel(x, kH / 2, image->red_mask);
    l.corner_r = channel(kW - 2, kH - 2, image->red_mask);
    l.corner_b = channel(kW - 2, kH - 2, image->blue_mask);
    XDestroyImage(image);
    return l;
  }
  void press(KeySym sym) const {
    XEvent key{};
    key.xkey.type = KeyPress;
    key.xkey.display = x_;
    key.xkey.window = window_;
    key.xkey.root = DefaultRootWindow(x_);
    key.xkey.keycode = XKeysymToKeycode(x_, sym);
    key.xkey.same_screen = True;
    XSendEvent(x_, window_, True, KeyPressMask, &key);
    XFlush(x_);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  void pointer(int type, int x, int y) const {
    XEvent e{};
    e.type = type;
    if (type == MotionNotify) {
      e.xmotion.window = window_;
      e.xmotion.x = x;
      e.xmotion.y = y;
      e.xmotion.same_screen = True;
    } else {
      e.xbutton.window = window_;
      e.xbutton.x = x;
      e.xbutton.y = y;
      e.xbutton.button = Button1;
      e.xbutton.same_screen = True;
    }
    XSendEvent(x_, window_, True,
               type == MotionNotify ? PointerMotionMask
                                    : (type == ButtonPress ? ButtonPressMask : ButtonReleaseMask),
               &e);
    XFlush(x_);
    std::this_thread::sleep_for(std::chrono::milliseconds(15));
  }

 private:
  ::Display* x_;
  Window window_ = 0;
};

std::string slurp(const std::string& path) {
  std::string text;
  if (FILE* f = std::fopen(path.c_str(), "r")) {
    char buf[4096];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof(buf), f)) > 0) text.append(buf, n);
    std::fclose(f);
  }
  return text;
}

TEST(PaintX11, OpensFullscreenDrawsTheCloudAndQuitsOnEsc) {
  if (!xvfbInstalled())
    GTEST_SKIP() << "SKIPPED LOUDLY: Xvfb is not installed (apt-get install xvfb)";
  Xvfb server(kW, kH);
  ASSERT_FALSE(server.name().empty());

  // The binary, in the background, its stdout/stderr in files.
  const std::string dir = std::string(CB_TEST_WORK);
  const std::string out = dir + "/paint_x11.out", err = dir + "/paint_x11.err";
  const std::string command = "DISPLAY=" + server.name() +
                              " LIBGL_ALWAYS_SOFTWARE=1 '" CB_CLOUDBRUSH_BIN "' --grid 48 >'" +
                              out + "' 2>'" + err + "'; echo $? >'" + dir + "/paint_x11.status'";
  std::remove((dir + "/paint_x11.status").c_str());
  std::thread runner([&] { std::system(command.c_str()); });

  Observer observer(server.name());
  ASSERT_TRUE(observer.open());
  // Wait for the window and the sky it opens on (blue corners: the first screen is the
  // paintable sky, with the hint over its middle).
  Window window = 0;
  bool sky_seen = false;
  for (int i = 0; i < 600 && !sky_seen; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!window) window = findWindowNamed(observer.display(), "cloudbrush");
    if (!window) continue;
    sky_seen = observer.look(kW / 2).sky();
  }
  ASSERT_NE(window, 0u) << "no window named cloudbrush appeared";
  observer.use(window);
  XWindowAttributes attributes{};
  XGetWindowAttributes(observer.display(), window, &attributes);
  EXPECT_EQ(attributes.width, kW);
  EXPECT_EQ(attributes.height, kH);
  EXPECT_TRUE(sky_seen) << "the screen never showed the sky";

  // The mode keys on X11: Canvas, Light, then Paint.
  observer.press(XK_2);
  observer.press(XK_5);
  observer.press(XK_3);
  // No tablet here: the mouse paints a stroke across the middle.
  observer.pointer(MotionNotify, kW / 4, kH / 2);
  observer.pointer(ButtonPress, kW / 4, kH / 2);
  for (int i = 0; i <= 40; ++i)
    observer.pointer(MotionNotify, kW / 4 + i * kW / 80, kH / 2 + int(10 * std::sin(i * 0.2)));
  observer.pointer(ButtonRelease, 3 * kW / 4, kH / 2);
  // The lifted stroke becomes a lit cloud where it was drawn (the hint is gone after it): a
  // bright middle on the sky.
  bool cloud_seen = false;
  for (int i = 0; i < 300 && !cloud_seen; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const Look l = observer.look(kW / 2);
    cloud_seen = l.sky() && l.centre_r > l.corner_r + 40;
  }
  EXPECT_TRUE(cloud_seen) << "the painted stroke never showed as a cloud in front of the sky";
  observer.press(XK_Escape);  // a stroke is unsaved: the painter asks first
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  observer.press(XK_Escape);  // and Esc again quits
  runner.join();  // the binary must end by itself after Esc Esc (ctest's timeout guards this)

  const std::string status = slurp(dir + "/paint_x11.status");
  const std::string stdout_text = slurp(out), stderr_text = slurp(err);
  EXPECT_EQ(status, "0\n") << stderr_text;
  EXPECT_NE(stderr_text.find("x11 display 320x200"), std::string::npos) << stderr_text;
  EXPECT_NE(stdout_text.find("on x11 (Esc)"), std::string::npos) << stdout_text;
  EXPECT_NE(stderr_text.find("cloudbrush: canvas\n"), std::string::npos) << stderr_text;
  EXPECT_NE(stderr_text.find("cloudbrush: light\n"), std::string::npos) << stderr_text;
  EXPECT_NE(stderr_text.find("the mouse paints"), std::string::npos) << stderr_text;
  EXPECT_NE(stdout_text.find(" 1 strokes mapped"), std::string::npos) << stdout_text;
}

}  // namespace
}  // namespace cb
