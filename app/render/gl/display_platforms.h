// Internal to app/render/gl: the constructor of each platform, used by openDisplay().
#pragma once

#include <memory>
#include <string>

#include "app/render/gl/display.h"

namespace cb {

std::unique_ptr<Display> openSurfacelessDisplay(const DisplayOptions& options, std::string* error);
std::unique_ptr<Display> openKmsDisplay(const DisplayOptions& options, std::string* error);
std::unique_ptr<Display> openX11Display(const DisplayOptions& options, std::string* error);

// CLOCK_MONOTONIC now, in nanoseconds (the clock of DRM vblank timestamps).
uint64_t monotonicNowNs();

}  // namespace cb
