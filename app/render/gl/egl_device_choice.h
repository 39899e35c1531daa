// Which EGL platform a headless context opens (createSurfacelessContext, the surfaceless display,
// the CLI's render and replay, the benches), chosen as `--display auto` chooses a platform: the
// best candidate first, and a note of why the ones before it were passed over.
//
//   1. a hardware device through EGL_EXT_platform_device (a device without
//      EGL_MESA_device_software: NVIDIA's driver, Mesa on a GPU), those with a DRM render node
//      first — NVIDIA's driver offers no EGL_MESA_platform_surfaceless, so this is how a kiosk
//      with a GPU renders headless;
//   2. EGL_MESA_platform_surfaceless (Mesa: a GPU's render node or llvmpipe, as before);
//   3. a software device through EGL_EXT_platform_device (EGL_MESA_device_software).
// CLOUDBRUSH_EGL_DEVICE overrides the choice: "surfaceless", or a device index.
// Pure logic over what EGL reports, so tests feed it made-up devices (egl_device_choice_test).
#pragma once

#include <string>
#include <vector>

namespace cb {

// One EGLDeviceEXT as eglQueryDevicesEXT lists it.
struct EglDeviceInfo {
  std::string extensions;   // eglQueryDeviceStringEXT(EGL_EXTENSIONS)
  std::string drm_node;     // EGL_DRM_DEVICE_FILE_EXT, "" if none
  std::string render_node;  // EGL_DRM_RENDER_NODE_FILE_EXT, "" if none
};

struct HeadlessEglChoice {
  enum class Kind { kDevice, kSurfaceless, kNone };
  Kind kind = Kind::kNone;
  int device = -1;          // kDevice: the index in the list
  std::string description;  // what was chosen, e.g. "EGL device 1 (/dev/dri/renderD128)"
  std::string passed_over;  // why earlier candidates were not taken ("" if none); kNone: why none
};

// Whether `extensions` (space-separated) holds `name` exactly.
bool hasEglExtension(const std::string& extensions, const std::string& name);

// `client_extensions`: eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS); `devices`: the devices
// listed (empty without EGL_EXT_device_enumeration); `override_choice`: CLOUDBRUSH_EGL_DEVICE
// ("" for none).
HeadlessEglChoice chooseHeadlessEgl(const std::string& client_extensions,
                                    const std::vector<EglDeviceInfo>& devices,
                                    const std::string& override_choice);

}  // namespace cb
