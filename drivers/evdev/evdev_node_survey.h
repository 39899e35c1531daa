// Every input event node as `cloudbrush devices` reports it when looking for a pen: a pen, a
// device that is not a pen (and what it looks like), or a node this user cannot open (and the
// error), so a missing tablet can be told apart from missing permissions.
#pragma once

#include <string>
#include <vector>

#include "drivers/core/pen_sample.h"

namespace cb {

enum class EvdevNodeKind { kPen, kNotAPen, kCannotOpen };

struct EvdevNodeReport {
  std::string path;
  EvdevNodeKind kind = EvdevNodeKind::kCannotOpen;
  std::string name;    // the device's name, when it could be opened
  std::string detail;  // not a pen: what it is instead; cannot open: the error
  bool permission_denied = false;
  PenDeviceInfo info;  // for pens
};

struct EvdevSurvey {
  std::string dir;
  std::string dir_error;  // set when the directory itself cannot be listed
  bool dir_permission_denied = false;
  std::vector<EvdevNodeReport> nodes;  // in node order (event2 before event10)
};

EvdevSurvey surveyEvdevNodes(const std::string& dir = "/dev/input");

}  // namespace cb
