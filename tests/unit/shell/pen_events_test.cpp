// Pen events come once per change, in libinput's fixed order, from the calibrated contact.
#include <gtest/gtest.h>

#include "app/shell/pen_events.h"

namespace cb {
namespace {

MappedSample sample(bool proximity, bool contact, uint32_t buttons = 0) {
  MappedSample s;
  s.in_proximity = proximity;
  s.contact = contact;
  s.raw.buttons = buttons;
  return s;
}

std::string names(const std::vector<PenEvent>& events) {
  std::string out;
  for (const PenEvent& e : events)
    out += std::string(out.empty() ? "" : " ") + penEventName(e.kind);
  return out;
}

TEST(PenEvents, FixedOrderOverAStroke) {
  PenEventDeriver deriver;
  std::vector<PenEvent> events;
  deriver.derive(sample(true, false), &events);
  EXPECT_EQ(names(events), "proximity-in hover");
  events.clear();
  deriver.derive(sample(true, true, kPenStylus2), &events);
  EXPECT_EQ(names(events), "hover down button-down");
  EXPECT_EQ(events[2].button, uint32_t(kPenStylus2));
  events.clear();
  deriver.derive(sample(true, true, kPenStylus2), &events);
  EXPECT_EQ(names(events), "drag");
  events.clear();
  // Lifted and out of range in one sample: button up, tip up, proximity out, in that order.
  deriver.derive(sample(false, false), &events);
  EXPECT_EQ(names(events), "button-up up proximity-out");
  EXPECT_FALSE(deriver.down());
  EXPECT_FALSE(deriver.inProximity());
}

}  // namespace
}  // namespace cb
