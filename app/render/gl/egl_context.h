// EGL display + OpenGL 4.5 core context creation shared by every platform (surfaceless,
// GBM/KMS, X11). Platform files only choose the EGLDisplay and the surface.
#pragma once

#include <string>

#include <EGL/egl.h>

namespace cb {

struct EglContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLConfig config = nullptr;
  EGLContext context = EGL_NO_CONTEXT;
  std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version;   // GL_VERSION
  std::string vendor;    // GL_VENDOR
  // The headless choice (egl_device_choice.h): which EGL platform/device, and why earlier
  // candidates were passed over ("" when none were).
  std::string device;
  std::string device_note;
  // "<device>: <GL_RENDERER>, <GL_VERSION> (<GL_VENDOR>)": what rendered, for logs and benches.
  std::string describe() const;
};

// Initialises `display`, picks a config matching `surface_type` (EGL_PBUFFER_BIT,
// EGL_WINDOW_BIT) and `native_visual` (0 = any), creates a 4.5 core context. On failure returns
// false with a message naming what was found and what is needed (e.g. the GL version).
bool createGlContext(EGLDisplay display, EGLint surface_type, EGLint native_visual, EglContext* out,
                     std::string* error);
// Checks that the current context is at least OpenGL 4.5 core; fills renderer/version.
bool checkGlVersion(EglContext* ctx, std::string* error);
void destroyGlContext(EglContext* ctx);

// A headless context, made current with no surface; render into framebuffer objects. The EGL
// platform is chosen by chooseHeadlessEgl (egl_device_choice.h): a hardware device through
// EGL_EXT_platform_device, else Mesa's surfaceless platform, else a software device; out->device
// says which. (The name is older than the choice.)
bool createSurfacelessContext(EglContext* out, std::string* error);

}  // namespace cb
