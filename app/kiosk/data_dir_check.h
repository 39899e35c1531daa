// Whether the kiosk can use its data dir: it exists (or can be made), is a folder, and a file can
// be created, written and removed in it. Checked at start-up so that an unusable data dir shows
// the kiosk's error screen (app/shell/kiosk/kiosk_error_screen.h) instead of failing later.
#pragma once

#include <string>

namespace cb {

// False with *error ("DIR: cannot write a file in it: Permission denied").
bool checkDataDir(const std::string& dir, std::string* error);

}  // namespace cb
