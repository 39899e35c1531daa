// A pen source that searches for ever and never finds a tablet: the painter then takes the mouse
// as the pen (PaintScreen::onPointer), as on a machine without a tablet. For benches and tests
// that drive the painter with injected mouse events.
#pragma once

#include <string>
#include <vector>

#include "drivers/core/pen_source.h"

namespace cb {

class NoPenSource final : public PenSource {
 public:
  const char* backendName() const override { return "none"; }
  void poll(int, std::vector<PenSample>&) override {}
  PenConnection connection() const override { return PenConnection::kSearching; }
  const PenDeviceInfo& deviceInfo() const override { return info_; }
  std::string statusMessage() const override { return "no tablet"; }

 private:
  PenDeviceInfo info_;
};

}  // namespace cb
