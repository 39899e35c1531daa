#include "drivers/evdev/evdev_node_survey.h"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "drivers/evdev/evdev_discovery.h"

namespace cb {
namespace {

// A short description of an input device that is not a pen, from its capabilities.
std::string whatItIs(libevdev* dev) {
  if (libevdev_has_event_code(dev, EV_KEY, BTN_TOOL_PEN))
    return "has BTN_TOOL_PEN but no ABS_X/ABS_Y";
  if (libevdev_has_event_code(dev, EV_ABS, ABS_MT_POSITION_X) ||
      libevdev_has_event_code(dev, EV_KEY, BTN_TOOL_FINGER))
    return "a touch screen or touchpad (no BTN_TOOL_PEN)";
  if (libevdev_has_event_code(dev, EV_REL, REL_X)) return "a mouse (no BTN_TOOL_PEN)";
  if (libevdev_has_event_code(dev, EV_KEY, KEY_A)) return "a keyboard (no BTN_TOOL_PEN)";
  if (libevdev_has_event_code(dev, EV_KEY, BTN_0)) return "a pad or buttons (no BTN_TOOL_PEN)";
  return "no BTN_TOOL_PEN";
}

int nodeNumber(const std::string& path) {
  const size_t at = path.rfind("event");
  return at == std::string::npos ? 0 : std::atoi(path.c_str() + at + 5);
}

}  // namespace

EvdevSurvey surveyEvdevNodes(const std::string& dir) {
  EvdevSurvey survey;
  survey.dir = dir;
  std::vector<EvdevNodeReport>& out = survey.nodes;
  std::error_code ec;
  std::vector<std::string> nodes;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("event", 0) == 0) nodes.push_back(e.path().string());
  }
  if (ec) {
    survey.dir_error = ec.message();
    survey.dir_permission_denied = ec == std::errc::permission_denied;
    return survey;
  }
  std::sort(nodes.begin(), nodes.end(), [](const std::string& a, const std::string& b) {
    return nodeNumber(a) < nodeNumber(b);
  });
  for (const std::string& path : nodes) {
    EvdevNodeReport r;
    r.path = path;
    const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
      r.permission_denied = errno == EACCES || errno == EPERM;
      r.detail = std::string("open: ") + std::strerror(errno);
      out.push_back(r);
      continue;
    }
    libevdev* dev = nullptr;
    const int rc = libevdev_new_from_fd(fd, &dev);
    if (rc != 0) {
      r.detail = std::string("not an input device: ") + std::strerror(-rc);
    } else {
      r.name = libevdev_get_name(dev) ? libevdev_get_name(dev) : "";
      if (isEvdevPen(dev)) {
        r.kind = EvdevNodeKind::kPen;
        r.info = evdevPenInfo(dev);
      } else {
        r.kind = EvdevNodeKind::kNotAPen;
        r.detail = whatItIs(dev);
      }
      libevdev_free(dev);
    }
    close(fd);
    out.push_back(r);
  }
  return survey;
}

}  // namespace cb
