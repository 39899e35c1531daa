// GBM/KMS platform: fullscreen on a DRM connector with no compositor (the kiosk path).
// The DRM side lives in display_kms_output.cpp; here EGL renders into a GBM surface whose front
// buffer is scanned out: the first frame by drmModeSetCrtc, every later one by a page flip whose
// event carries the vblank sequence and timestamp (kept in the FrameTimingRing).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <gbm.h>
#include <unistd.h>
#include <xf86drm.h>

#include <cstdio>

#include "app/render/gl/display_kms_output.h"
#include "app/render/gl/display_kms_vt.h"
#include "app/render/gl/display_platforms.h"

namespace cb {
namespace {

constexpr int kFlipTimeoutMs = 2000;

// A DRM framebuffer per GBM buffer, made on first use and removed with the buffer.
void destroyFramebuffer(gbm_bo* bo, void* data) {
  const uint32_t fb_id = uint32_t(reinterpret_cast<uintptr_t>(data));
  if (fb_id) drmModeRmFB(gbm_device_get_fd(gbm_bo_get_device(bo)), fb_id);
}

class KmsDisplay final : public Display {
 public:
  ~KmsDisplay() override {
    if (context_.display != EGL_NO_DISPLAY) {
      eglMakeCurrent(context_.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (shown_bo_) gbm_surface_release_buffer(surface_, shown_bo_);
      if (egl_surface_ != EGL_NO_SURFACE) eglDestroySurface(context_.display, egl_surface_);
    }
    destroyGlContext(&context_);
    if (surface_) gbm_surface_destroy(surface_);
    if (gbm_) gbm_device_destroy(gbm_);
    closeKmsOutput(&output_);
  }

  bool open(const DisplayOptions& options, std::string* error) {
    if (!openKmsOutput(options.drm_device, &output_, error)) return false;
    width_ = output_.mode.hdisplay;
    height_ = output_.mode.vdisplay;
    const std::string where = output_.device + " " + output_.connector_name;
    gbm_ = gbm_create_device(output_.fd);
    if (!gbm_) {
      *error = where + ": gbm_create_device failed";
      return false;
    }
    surface_ = gbm_surface_create(gbm_, uint32_t(width_), uint32_t(height_), GBM_FORMAT_XRGB8888,
                                  GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
    if (!surface_) {
      *error = where + ": gbm_surface_create " + std::to_string(width_) + "x" +
               std::to_string(height_) + " XRGB8888 failed";
      return false;
    }
    EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_GBM_KHR, gbm_, nullptr);
    if (display == EGL_NO_DISPLAY) {
      *error = where + ": no EGL display on GBM (needs EGL_KHR_platform_gbm, libegl-mesa0)";
      return false;
    }
    if (!createGlContext(display, EGL_WINDOW_BIT, GBM_FORMAT_XRGB8888, &context_, error)) {
      *error = where + ": " + *error;
      return false;
    }
    EGLint visual = 0;
    eglGetConfigAttrib(display, context_.config, EGL_NATIVE_VISUAL_ID, &visual);
    if (visual != GBM_FORMAT_XRGB8888) {
      *error = where + ": no EGL config renders to XRGB8888 GBM buffers";
      return false;
    }
    egl_surface_ = eglCreatePlatformWindowSurface(display, context_.config, surface_, nullptr);
    if (egl_surface_ == EGL_NO_SURFACE) {
      *error = where + ": eglCreatePlatformWindowSurface failed (EGL error " +
               std::to_string(eglGetError()) + ")";
      return false;
    }
    if (!makeCurrent(error)) return false;
    if (!checkGlVersion(&context_, error)) {
      *error = where + ": " + *error;
      return false;
    }
    glViewport(0, 0, width_, height_);
    if (options.lock_vt) {
      std::string why;
      vt_ = VtLock::lock(STDIN_FILENO, &why);
      if (vt_)
        std::fprintf(stderr,
                     "cloudbrush: kms: VT %d locked: the console takes no keys (K_OFF) and "
                     "refuses VT switches (VT_PROCESS)\n",
                     vt_->number());
      else
        std::fprintf(stderr, "cloudbrush: kms: VT switching is NOT blocked: %s\n", why.c_str());
    }
    return true;
  }

  const char* platformName() const override { return "kms"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  GLuint framebuffer() const override { return 0; }

  bool makeCurrent(std::string* error) override {
    if (eglMakeCurrent(context_.display, egl_surface_, egl_surface_, context_.context)) return true;
    if (error) *error = output_.device + ": eglMakeCurrent on the GBM surface failed";
    return false;
  }

  bool present(std::string* error) override {
    FrameTiming timing;
    timing.frame = timings_.total() + 1;
    timing.submit_ns = monotonicNowNs();
    if (!eglSwapBuffers(context_.display, egl_surface_)) {
      *error = output_.device + ": eglSwapBuffers failed (EGL error " +
               std::to_string(eglGetError()) + ")";
      return false;
    }
    gbm_bo* next = gbm_surface_lock_front_buffer(surface_);
    if (!next) {
      *error = output_.device + ": gbm_surface_lock_front_buffer failed";
      return false;
    }
    uint32_t fb_id = 0;
    if (!framebufferFor(next, &fb_id, error)) {
      gbm_surface_release_buffer(surface_, next);
      return false;
    }
    if (!output_.mode_set) {
      // The first frame sets the mode; there is no flip event for it.
      if (!setKmsMode(&output_, fb_id, error)) {
        gbm_surface_release_buffer(surface_, next);
        return false;
      }
      timing.shown_ns = monotonicNowNs();
    } else {
      KmsFlipEvent flip;
      if (!queueKmsPageFlip(output_, fb_id, &flip, error) ||
          !waitKmsPageFlip(output_, kFlipTimeoutMs, &flip, error)) {
        gbm_surface_release_buffer(surface_, next);
        return false;
      }
      timing.shown_ns = flip.vblank_ns;
      timing.vblank_sequence = flip.sequence;
      timing.has_vblank = true;
    }
    if (shown_bo_) gbm_surface_release_buffer(surface_, shown_bo_);
    shown_bo_ = next;
    timings_.push(timing);
    return true;
  }

  // Keys come from the keyboards through evdev, read by the caller (drivers/keyboard).
  std::vector<DisplayEvent> pollEvents() override { return {}; }
  bool needsEvdevKeyboard() const override { return true; }
  std::optional<double> refreshHz(std::string* why_unknown) const override {
    std::string why;
    const std::optional<double> hz = kmsModeRefreshHz(output_.mode, &why);
    if (!hz && why_unknown) *why_unknown = output_.device + ": " + why;
    return hz;
  }

 private:
  bool framebufferFor(gbm_bo* bo, uint32_t* fb_id, std::string* error) {
    if (void* cached = gbm_bo_get_user_data(bo)) {
      *fb_id = uint32_t(reinterpret_cast<uintptr_t>(cached));
      return true;
    }
    if (!addKmsFramebuffer(output_, gbm_bo_get_width(bo), gbm_bo_get_height(bo),
                           gbm_bo_get_format(bo), gbm_bo_get_handle(bo).u32, gbm_bo_get_stride(bo),
                           fb_id, error))
      return false;
    gbm_bo_set_user_data(bo, reinterpret_cast<void*>(uintptr_t(*fb_id)), destroyFramebuffer);
    return true;
  }

  std::unique_ptr<VtLock> vt_;  // first: restored after everything else is closed
  KmsOutput output_;
  gbm_device* gbm_ = nullptr;
  gbm_surface* surface_ = nullptr;
  EGLSurface egl_surface_ = EGL_NO_SURFACE;
  gbm_bo* shown_bo_ = nullptr;  // the buffer being scanned out
  int width_ = 0, height_ = 0;
};

}  // namespace

std::unique_ptr<Display> openKmsDisplay(const DisplayOptions& options, std::string* error) {
  auto display = std::make_unique<KmsDisplay>();
  if (!display->open(options, error)) return nullptr;
  return display;
}

}  // namespace cb
