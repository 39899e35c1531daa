#include "app/render/gl/egl_context.h"

#include <cstdlib>
#include <cstring>
#include <vector>

#include <EGL/eglext.h>

#include "app/render/gl/egl_device_choice.h"
#include "app/render/gl/gl.h"

namespace cb {

bool createGlContext(EGLDisplay display, EGLint surface_type, EGLint native_visual, EglContext* out,
                     std::string* error) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    *error = "eglInitialize failed (EGL error 0x" + std::to_string(eglGetError()) + ")";
    return false;
  }
  out->display = display;
  if (!eglBindAPI(EGL_OPENGL_API)) {
    *error = "EGL " + std::to_string(major) + "." + std::to_string(minor) +
             " cannot bind the desktop OpenGL API";
    return false;
  }
  const EGLint attribs[] = {EGL_SURFACE_TYPE,
                            surface_type,
                            EGL_RENDERABLE_TYPE,
                            EGL_OPENGL_BIT,
                            EGL_RED_SIZE,
                            8,
                            EGL_GREEN_SIZE,
                            8,
                            EGL_BLUE_SIZE,
                            8,
                            EGL_NONE};
  EGLint count = 0;
  EGLConfig configs[64];
  if (!eglChooseConfig(display, attribs, configs, 64, &count) || count == 0) {
    if (surface_type != 0) {
      *error = "no EGL config with an OpenGL renderable surface of the wanted type";
      return false;
    }
  }
  out->config = count > 0 ? configs[0] : nullptr;
  for (EGLint i = 0; i < count && native_visual != 0; ++i) {
    EGLint id = 0;
    eglGetConfigAttrib(display, configs[i], EGL_NATIVE_VISUAL_ID, &id);
    if (id == native_visual) {
      out->config = configs[i];
      break;
    }
  }
  const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                4,
                                EGL_CONTEXT_MINOR_VERSION,
                                5,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                EGL_NONE};
  out->context = eglCreateContext(display, out->config, EGL_NO_CONTEXT, ctx_attribs);
  if (out->context == EGL_NO_CONTEXT) {
    // Say what the driver offers: make a default context and read its version.
    const EGLint any[] = {EGL_NONE};
    EGLContext probe = eglCreateContext(display, out->config, EGL_NO_CONTEXT, any);
    std::string found = "unknown";
    if (probe != EGL_NO_CONTEXT && eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, probe)) {
      const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
      if (v) found = v;
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    if (probe != EGL_NO_CONTEXT) eglDestroyContext(display, probe);
    *error = "OpenGL 4.5 core profile is needed; the driver offers OpenGL " + found;
    return false;
  }
  return true;
}

bool checkGlVersion(EglContext* ctx, std::string* error) {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const char* vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
  ctx->vendor = vendor ? vendor : "";
  ctx->renderer = r ? r : "";
  ctx->version = v ? v : "";
  if (major * 10 + minor < 45) {
    *error =
        "OpenGL 4.5 core profile is needed; found OpenGL " + ctx->version + " on " + ctx->renderer;
    return false;
  }
  return true;
}

void destroyGlContext(EglContext* ctx) {
  if (ctx->display == EGL_NO_DISPLAY) return;
  eglMakeCurrent(ctx->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (ctx->context != EGL_NO_CONTEXT) eglDestroyContext(ctx->display, ctx->context);
  eglTerminate(ctx->display);
  *ctx = EglContext{};
}

std::string EglContext::describe() const {
  return device + ": " + renderer + ", " + version + (vendor.empty() ? "" : " (" + vendor + ")");
}

namespace {

// The devices eglQueryDevicesEXT lists (empty without EGL_EXT_device_enumeration).
std::vector<EGLDeviceEXT> queryEglDevices(std::vector<EglDeviceInfo>* infos) {
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  std::vector<EGLDeviceEXT> devices;
  EGLint count = 0;
  if (!query_devices || !query_string || !query_devices(0, nullptr, &count) || count <= 0)
    return devices;
  devices.resize(size_t(count));
  if (!query_devices(count, devices.data(), &count)) count = 0;
  devices.resize(size_t(count));
  for (EGLDeviceEXT d : devices) {
    EglDeviceInfo info;
    const char* ext = query_string(d, EGL_EXTENSIONS);
    info.extensions = ext ? ext : "";
    if (hasEglExtension(info.extensions, "EGL_EXT_device_drm")) {
      const char* node = query_string(d, EGL_DRM_DEVICE_FILE_EXT);
      info.drm_node = node ? node : "";
    }
#ifdef EGL_DRM_RENDER_NODE_FILE_EXT
    if (hasEglExtension(info.extensions, "EGL_EXT_device_drm_render_node")) {
      const char* node = query_string(d, EGL_DRM_RENDER_NODE_FILE_EXT);
      info.render_node = node ? node : "";
    }
#endif
    infos->push_back(info);
  }
  eglGetError();  // a string a device lacks leaves an error behind
  return devices;
}

}  // namespace

bool createSurfacelessContext(EglContext* out, std::string* error) {
  const char* exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const std::string client = exts ? exts : "";
  std::vector<EglDeviceInfo> infos;
  const std::vector<EGLDeviceEXT> devices = hasEglExtension(client, "EGL_EXT_platform_device")
                                                ? queryEglDevices(&infos)
                                                : std::vector<EGLDeviceEXT>{};
  const char* override_choice = std::getenv("CLOUDBRUSH_EGL_DEVICE");
  const HeadlessEglChoice choice =
      chooseHeadlessEgl(client, infos, override_choice ? override_choice : "");
  if (choice.kind == HeadlessEglChoice::Kind::kNone) {
    *error = "no headless EGL platform: " + choice.passed_over;
    return false;
  }
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay display =
      !get_platform_display ? EGL_NO_DISPLAY
      : choice.kind == HeadlessEglChoice::Kind::kDevice
          ? get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[size_t(choice.device)], nullptr)
          : get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) {
    *error = "cannot open the EGL display of " + choice.description;
    return false;
  }
  if (!createGlContext(display, EGL_PBUFFER_BIT, 0, out, error)) {
    *error = choice.description + ": " + *error;
    destroyGlContext(out);
    return false;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, out->context)) {
    *error = choice.description +
             ": eglMakeCurrent without a surface failed (needs EGL_KHR_surfaceless_context)";
    destroyGlContext(out);
    return false;
  }
  if (!checkGlVersion(out, error)) {
    destroyGlContext(out);
    return false;
  }
  out->device = choice.description;
  out->device_note = choice.passed_over;
  return true;
}

}  // namespace cb
