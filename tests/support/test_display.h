// The display screen tests draw into: EGL surfaceless on llvmpipe, width × height.
#pragma once

#include <memory>
#include <string>

#include "app/render/gl/display.h"

namespace cb::test {

// Null with *error when no display could be opened.
std::unique_ptr<Display> openTestDisplay(int width, int height, std::string* error);

}  // namespace cb::test
