#include "tests/support/test_display.h"

namespace cb::test {

std::unique_ptr<Display> openTestDisplay(int width, int height, std::string* error) {
  DisplayOptions options;
  options.platform = DisplayPlatform::Surfaceless;
  options.width = width;
  options.height = height;
  return openDisplay(options, error);
}

}  // namespace cb::test
