// The administrator's layer over the shipped configuration (config_paths.h): <dir>/name when it
// exists, else "". <dir> is CLOUDBRUSH_CONFIG_OVERRIDE_DIR, else /etc/cloudbrush for an
// installed binary (none for a binary run from its build tree). kiosk.toml and brush.toml are
// read key by key over the defaults (a key the /etc file sets wins, the others stay). Paths
// compiled in from the build machine (the source tree's config/, its HID fixtures) are likewise
// read only by a binary run from its build tree: an installed binary never looks there, so a
// local user who creates that path on a kiosk cannot set its settings.
#pragma once

#include <string>

namespace cb {

std::string configOverrideFile(const std::string& name);

}  // namespace cb
