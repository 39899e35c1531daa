// The kiosk's files are written with the project's one atomic writer (app/core/atomic_file.h:
// temporary in the same folder, fsync, rename, fsync of the folder); this header is kept so the
// kiosk's includes keep working.
#pragma once

#include "app/core/atomic_file.h"
