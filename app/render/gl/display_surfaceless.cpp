// Surfaceless platform: a headless EGL context (EGL_MESA_platform_surfaceless) drawing into an
// offscreen framebuffer object of the requested size. present() finishes the frame; there is no
// screen, so there are no vblanks and no input devices; events queued with injectEvent() are
// delivered.
#include "app/render/gl/display_platforms.h"

namespace cb {
namespace {

class SurfacelessDisplay final : public Display {
 public:
  ~SurfacelessDisplay() override {
    if (context_.display != EGL_NO_DISPLAY && makeCurrent(nullptr)) {
      glDeleteFramebuffers(1, &fbo_);
      glDeleteRenderbuffers(2, renderbuffers_);
    }
    destroyGlContext(&context_);
  }

  bool open(const DisplayOptions& options, std::string* error) {
    if (options.width <= 0 || options.height <= 0 || options.width > 16384 ||
        options.height > 16384) {
      *error = "surfaceless display: size " + std::to_string(options.width) + "x" +
               std::to_string(options.height) + " is out of range (1..16384)";
      return false;
    }
    width_ = options.width;
    height_ = options.height;
    if (!createSurfacelessContext(&context_, error)) return false;
    glCreateRenderbuffers(2, renderbuffers_);
    glNamedRenderbufferStorage(renderbuffers_[0], GL_RGBA8, width_, height_);
    glNamedRenderbufferStorage(renderbuffers_[1], GL_DEPTH24_STENCIL8, width_, height_);
    glCreateFramebuffers(1, &fbo_);
    glNamedFramebufferRenderbuffer(fbo_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers_[0]);
    glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                                   renderbuffers_[1]);
    const GLenum status = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      *error = "surfaceless display: offscreen framebuffer incomplete (status 0x" +
               std::to_string(status) + ")";
      return false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, width_, height_);
    return true;
  }

  const char* platformName() const override { return "surfaceless"; }
  int width() const override { return width_; }
  int height() const override { return height_; }
  GLuint framebuffer() const override { return fbo_; }

  bool makeCurrent(std::string* error) override {
    if (eglMakeCurrent(context_.display, EGL_NO_SURFACE, EGL_NO_SURFACE, context_.context))
      return true;
    if (error) *error = "surfaceless display: eglMakeCurrent failed";
    return false;
  }

  bool present(std::string* error) override {
    FrameTiming timing;
    timing.frame = timings_.total() + 1;
    timing.submit_ns = monotonicNowNs();
    glFinish();
    timing.shown_ns = monotonicNowNs();
    timings_.push(timing);
    if (glGetError() != GL_NO_ERROR) {
      *error = "surfaceless display: GL error while finishing the frame";
      return false;
    }
    return true;
  }

  // No keyboard: only what injectEvent() queued, in order.
  std::optional<double> refreshHz(std::string* why_unknown) const override {
    if (why_unknown) *why_unknown = "surfaceless: an offscreen buffer, no display refresh";
    return std::nullopt;
  }
  std::vector<DisplayEvent> pollEvents() override {
    std::vector<DisplayEvent> events;
    events.swap(injected_);
    return events;
  }

 private:
  int width_ = 0, height_ = 0;
  GLuint fbo_ = 0;
  GLuint renderbuffers_[2] = {0, 0};
};

}  // namespace

std::unique_ptr<Display> openSurfacelessDisplay(const DisplayOptions& options, std::string* error) {
  auto display = std::make_unique<SurfacelessDisplay>();
  if (!display->open(options, error)) return nullptr;
  return display;
}

}  // namespace cb
