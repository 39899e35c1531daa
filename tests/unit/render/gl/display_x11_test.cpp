// The X11 platform under a real X server: the test starts Xvfb on a free display number, opens
// the fullscreen window on it, draws, and checks from a second client what the server shows.
#include <gtest/gtest.h>

#include "app/render/gl/display.h"
#include "app/shell/keymap.h"
#include "xvfb_server.h"

// After gtest: Xlib's macros (None, Bool, ...) would break its headers.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>

#include "x11_window.h"

#include <chrono>
#include <csignal>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

namespace cb {
namespace {

constexpr int kScreenW = 320, kScreenH = 200;

// Polls the display until an event matching `want` arrives (2 s at most).
template <typename Pred>
bool waitForEvent(Display& display, Pred want) {
  for (int i = 0; i < 200; ++i) {
    for (const DisplayEvent& e : display.pollEvents())
      if (want(e)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(X11Display, FullscreenWindowShowsTheFrameAndQuitsOnEscAndClose) {
  if (!xvfbInstalled())
    GTEST_SKIP() << "SKIPPED LOUDLY: Xvfb is not installed (apt-get install xvfb)";
  Xvfb server(kScreenW, kScreenH);
  ASSERT_FALSE(server.name().empty()) << "Xvfb did not report a display number";

  DisplayOptions options;
  options.platform = DisplayPlatform::X11;
  options.x11_display = server.name();
  std::string error;
  auto display = openDisplay(options, &error);
  ASSERT_NE(display, nullptr) << error;
  EXPECT_STREQ(display->platformName(), "x11");
  EXPECT_EQ(display->width(), kScreenW);
  EXPECT_EQ(display->height(), kScreenH);

  // Top half red, bottom half green.
  glBindFramebuffer(GL_FRAMEBUFFER, display->framebuffer());
  glViewport(0, 0, kScreenW, kScreenH);
  glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, kScreenH / 2, kScreenW, kScreenH / 2);
  glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  ASSERT_TRUE(display->present(&error)) << error;
  glFinish();
  EXPECT_EQ(display->frameTimings().size(), 1u);

  // A second client sees a mapped, screen-sized window asking to be fullscreen ...
  ::Display* observer = XOpenDisplay(server.name().c_str());
  ASSERT_NE(observer, nullptr);
  const Window window = findWindowNamed(observer, "cloudbrush");
  ASSERT_NE(window, 0u);
  XWindowAttributes attributes{};
  XGetWindowAttributes(observer, window, &attributes);
  EXPECT_EQ(attributes.x, 0);
  EXPECT_EQ(attributes.y, 0);
  EXPECT_EQ(attributes.width, kScreenW);
  EXPECT_EQ(attributes.height, kScreenH);
  EXPECT_EQ(attributes.map_state, IsViewable);
  Atom type = 0;
  int format = 0;
  unsigned long items = 0, after = 0;
  unsigned char* data = nullptr;
  XGetWindowProperty(observer, window, XInternAtom(observer, "_NET_WM_STATE", False), 0, 8, False,
                     XA_ATOM, &type, &format, &items, &after, &data);
  ASSERT_EQ(items, 1u);
  EXPECT_EQ(reinterpret_cast<Atom*>(data)[0],
            XInternAtom(observer, "_NET_WM_STATE_FULLSCREEN", False));
  XFree(data);

  // ... and the frame on the screen itself.
  XImage* image = XGetImage(observer, DefaultRootWindow(observer), 0, 0, kScreenW, kScreenH,
                            AllPlanes, ZPixmap);
  ASSERT_NE(image, nullptr);
  int top = 0, red_top = 0, bottom = 0, green_bottom = 0;
  for (int y = 0; y < kScreenH; y += 7) {
    for (int x = 0; x < kScreenW; x += 7) {
      const unsigned long p = XGetPixel(image, x, y);
      if (y < kScreenH / 2) {
        ++top;
        red_top += p == image->red_mask;
      } else {
        ++bottom;
        green_bottom += p == image->green_mask;
      }
    }
  }
  EXPECT_EQ(red_top, top) << "top half is not the red that was drawn";
  EXPECT_EQ(green_bottom, bottom) << "bottom half is not the green that was drawn";
  XDestroyImage(image);

  // Esc (a key press delivered to the window) is reported as its keysym; the keymap makes it a
  // quit request.
  XEvent key{};
  key.xkey.type = KeyPress;
  key.xkey.display = observer;
  key.xkey.window = window;
  key.xkey.root = DefaultRootWindow(observer);
  key.xkey.keycode = XKeysymToKeycode(observer, XK_Escape);
  key.xkey.same_screen = True;
  XSendEvent(observer, window, True, KeyPressMask, &key);
  XFlush(observer);
  EXPECT_TRUE(waitForEvent(*display, [](const DisplayEvent& e) {
    return e.kind == DisplayEvent::Kind::KeyDown && e.keysym == XK_Escape &&
           commandFor(e) == Command::kQuit;
  }));

  // Closing the window (WM_DELETE_WINDOW, as a window manager sends it) is a quit request.
  XEvent close_request{};
  close_request.xclient.type = ClientMessage;
  close_request.xclient.window = window;
  close_request.xclient.message_type = XInternAtom(observer, "WM_PROTOCOLS", False);
  close_request.xclient.format = 32;
  close_request.xclient.data.l[0] = long(XInternAtom(observer, "WM_DELETE_WINDOW", False));
  XSendEvent(observer, window, False, NoEventMask, &close_request);
  XFlush(observer);
  EXPECT_TRUE(waitForEvent(*display, [](const DisplayEvent& e) {
    return e.kind == DisplayEvent::Kind::Quit && commandFor(e) == Command::kQuit;
  }));
  XCloseDisplay(observer);
  display.reset();
}

}  // namespace
}  // namespace cb
