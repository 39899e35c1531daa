#include "app/render/gl/egl_device_choice.h"

#include <cstdlib>
#include <sstream>

namespace cb {
namespace {

bool isSoftware(const EglDeviceInfo& d) {
  return hasEglExtension(d.extensions, "EGL_MESA_device_software");
}

std::string describeDevice(int index, const EglDeviceInfo& d) {
  std::string s = "EGL device " + std::to_string(index);
  const std::string& node = !d.render_node.empty() ? d.render_node : d.drm_node;
  if (isSoftware(d))
    s += " (software)";
  else if (!node.empty())
    s += " (" + node + ")";
  return s;
}

void addNote(std::string* notes, const std::string& note) {
  if (!notes->empty()) *notes += "; ";
  *notes += note;
}

}  // namespace

bool hasEglExtension(const std::string& extensions, const std::string& name) {
  std::istringstream words(extensions);
  std::string word;
  while (words >> word)
    if (word == name) return true;
  return false;
}

HeadlessEglChoice chooseHeadlessEgl(const std::string& client_extensions,
                                    const std::vector<EglDeviceInfo>& devices,
                                    const std::string& override_choice) {
  HeadlessEglChoice choice;
  const bool platform_device = hasEglExtension(client_extensions, "EGL_EXT_platform_device");
  const bool surfaceless = hasEglExtension(client_extensions, "EGL_MESA_platform_surfaceless");
  const int count = platform_device ? int(devices.size()) : 0;
  if (!override_choice.empty()) {
    if (override_choice == "surfaceless" && surfaceless) {
      choice.kind = HeadlessEglChoice::Kind::kSurfaceless;
      choice.description = "surfaceless (CLOUDBRUSH_EGL_DEVICE)";
      return choice;
    }
    char* end = nullptr;
    const long index = std::strtol(override_choice.c_str(), &end, 10);
    if (end && *end == '\0' && index >= 0 && index < count) {
      choice.kind = HeadlessEglChoice::Kind::kDevice;
      choice.device = int(index);
      choice.description =
          describeDevice(choice.device, devices[size_t(index)]) + " (CLOUDBRUSH_EGL_DEVICE)";
      return choice;
    }
    addNote(&choice.passed_over, "CLOUDBRUSH_EGL_DEVICE=" + override_choice +
                                     " names no available device (0.." + std::to_string(count - 1) +
                                     " or surfaceless)");
  }
  if (!platform_device) addNote(&choice.passed_over, "no EGL_EXT_platform_device");
  // 1. Hardware devices, those with a render node first.
  int best = -1;
  for (int i = 0; i < count; ++i) {
    const EglDeviceInfo& d = devices[size_t(i)];
    if (isSoftware(d)) continue;
    if (best < 0 || (devices[size_t(best)].render_node.empty() && !d.render_node.empty())) best = i;
  }
  if (best >= 0) {
    choice.kind = HeadlessEglChoice::Kind::kDevice;
    choice.device = best;
    choice.description = describeDevice(best, devices[size_t(best)]);
    return choice;
  }
  if (platform_device) addNote(&choice.passed_over, "no hardware EGL device");
  // 2. Mesa's surfaceless platform.
  if (surfaceless) {
    choice.kind = HeadlessEglChoice::Kind::kSurfaceless;
    choice.description = "surfaceless (EGL_MESA_platform_surfaceless)";
    return choice;
  }
  addNote(&choice.passed_over, "no EGL_MESA_platform_surfaceless");
  // 3. A software device.
  for (int i = 0; i < count; ++i) {
    choice.kind = HeadlessEglChoice::Kind::kDevice;
    choice.device = i;
    choice.description = describeDevice(i, devices[size_t(i)]);
    return choice;
  }
  addNote(&choice.passed_over,
          "no EGL device at all (install libegl-mesa0, or a GPU's EGL driver)");
  return choice;
}

}  // namespace cb
