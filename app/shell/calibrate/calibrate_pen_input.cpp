#include "app/shell/calibrate/calibrate_pen_input.h"

#include "drivers/core/journal.h"

namespace cb {

void CalibratePenInput::start(const CalibrationProfile& profile, const PenDeviceInfo& device,
                              int width, int height) {
  calibrator_ = std::make_unique<Calibrator>(profile, device, width, height);
  deriver_ = PenEventDeriver{};
  in_range_ = false;
}

void CalibratePenInput::feed(const std::vector<PenSample>& samples,
                             const std::function<void(const CalibratePenEvent&)>& on_event) {
  std::vector<PenEvent> events;
  for (const PenSample& sample : samples) {
    if (!calibrator_) continue;
    if (journal_) journal_->appendPenSample(sample);
    last_t_ns_ = sample.t_ns;
    if (sample.tool_serial) tool_serial_ = sample.tool_serial;
    const MappedSample mapped = calibrator_->process(sample);
    in_range_ = mapped.in_proximity;
    if (mapped.in_proximity) cursor_ = {mapped.preview_x_px, mapped.preview_y_px};
    events.clear();
    deriver_.derive(mapped, &events);
    for (const PenEvent& event : events) on_event({event, mapped});
  }
}

std::optional<glm::dvec2> collectTap(TapCollector& collector, const CalibratePenEvent& e) {
  const glm::dvec2 mm(e.sample.raw.x_mm, e.sample.raw.y_mm);
  switch (e.event.kind) {
    case PenEvent::Kind::kDown:
      collector.down(mm);
      return std::nullopt;
    case PenEvent::Kind::kDrag:
      collector.move(mm);
      return std::nullopt;
    case PenEvent::Kind::kUp:
      return collector.up();
    default:
      return std::nullopt;
  }
}

}  // namespace cb
