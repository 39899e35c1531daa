// openDisplay(): the automatic platform choice and the parts every platform shares.
#include "app/render/gl/display.h"

#include <algorithm>
#include <cstdlib>
#include <ctime>

#include "app/render/gl/display_platforms.h"

namespace cb {

const char* displayPlatformName(DisplayPlatform platform) {
  switch (platform) {
    case DisplayPlatform::Auto:
      return "auto";
    case DisplayPlatform::Kms:
      return "kms";
    case DisplayPlatform::X11:
      return "x11";
    case DisplayPlatform::Surfaceless:
      return "surfaceless";
  }
  return "?";
}

bool parseDisplayPlatform(std::string_view text, DisplayPlatform* out) {
  for (DisplayPlatform p : {DisplayPlatform::Auto, DisplayPlatform::Kms, DisplayPlatform::X11,
                            DisplayPlatform::Surfaceless}) {
    if (text == displayPlatformName(p)) {
      *out = p;
      return true;
    }
  }
  return false;
}

uint64_t monotonicNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}

bool Display::readPixels(std::vector<uint8_t>* rgba) const {
  const int w = width(), h = height();
  rgba->assign(size_t(w) * size_t(h) * 4, 0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer());
  if (framebuffer() == 0) glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<uint8_t> bottom_up(rgba->size());
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  if (glGetError() != GL_NO_ERROR) return false;
  const size_t row = size_t(w) * 4;
  for (int y = 0; y < h; ++y)
    std::copy_n(bottom_up.data() + size_t(h - 1 - y) * row, row, rgba->data() + size_t(y) * row);
  return true;
}

std::unique_ptr<Display> openDisplay(const DisplayOptions& options, std::string* error,
                                     std::string* choice_note) {
  switch (options.platform) {
    case DisplayPlatform::Kms:
      return openKmsDisplay(options, error);
    case DisplayPlatform::X11:
      return openX11Display(options, error);
    case DisplayPlatform::Surfaceless:
      return openSurfacelessDisplay(options, error);
    case DisplayPlatform::Auto:
      break;
  }
  // Automatic: KMS if it can take the display (DRM master on a card with a connected
  // connector), else X11 if DISPLAY is set, else surfaceless. Each refusal is kept so that a
  // surprising choice can be explained.
  std::string why_not_kms, why_not_x11;
  if (auto kms = openKmsDisplay(options, &why_not_kms)) return kms;
  const char* display_env = std::getenv("DISPLAY");
  if (!options.x11_display.empty() || (display_env && *display_env)) {
    if (auto x11 = openX11Display(options, &why_not_x11)) {
      if (choice_note) *choice_note = "kms: " + why_not_kms;
      return x11;
    }
  } else {
    why_not_x11 = "DISPLAY is not set";
  }
  std::string why_not_surfaceless;
  if (auto headless = openSurfacelessDisplay(options, &why_not_surfaceless)) {
    if (choice_note) *choice_note = "kms: " + why_not_kms + "; x11: " + why_not_x11;
    return headless;
  }
  *error = "no display could be opened: kms: " + why_not_kms + "; x11: " + why_not_x11 +
           "; surfaceless: " + why_not_surfaceless;
  return nullptr;
}

}  // namespace cb
