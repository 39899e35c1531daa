// A rectangle of footprint pixels, half-open [x0, x1) × [y0, y1). Each brush call returns the
// rectangle it changed so the live overlay uploads only that part of the footprint.
#pragma once

#include <algorithm>

namespace cb {

struct FootprintRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int width() const { return empty() ? 0 : x1 - x0; }
  int height() const { return empty() ? 0 : y1 - y0; }

  // The smallest rectangle holding both (an empty rectangle adds nothing).
  FootprintRect united(const FootprintRect& o) const {
    if (o.empty()) return *this;
    if (empty()) return o;
    return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
  }
  FootprintRect clipped(int width, int height) const {
    FootprintRect r{std::max(x0, 0), std::max(y0, 0), std::min(x1, width), std::min(y1, height)};
    return r.empty() ? FootprintRect{} : r;
  }
};

}  // namespace cb
