#include "drivers/evdev/evdev_pen_state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "drivers/core/pen_units.h"

namespace cb {
namespace {

// The ranges the kernel's wacom driver gives the PTH-660 pen (fixtures/hid/README.md).
PenDeviceInfo pth660() {
  PenDeviceInfo d;
  d.x_max = 44800;
  d.y_max = 29600;
  d.x_res = d.y_res = 200;
  d.pressure_max = 8191;
  d.tilt_min = -64;
  d.tilt_max = 63;
  d.tilt_res = 57 * M_PI / 180.0;
  d.distance_max = 63;
  return d;
}

input_event ev(int64_t usec, uint16_t type, uint16_t code, int32_t value) {
  input_event e{};
  e.input_event_sec = usec / 1000000;
  e.input_event_usec = usec % 1000000;
  e.type = type;
  e.code = code;
  e.value = value;
  return e;
}

std::vector<PenSample> feedAll(EvdevPenState& state, const std::vector<input_event>& events) {
  std::vector<PenSample> out;
  for (const input_event& e : events) {
    PenSample s;
    if (state.feed(e, s)) out.push_back(s);
  }
  return out;
}

// A stroke as the wacom driver emits it: axes, keys, MSC_SERIAL, ABS_MISC, SYN_REPORT per report;
// the leaving frame zeroes the axes and releases the tool.
const std::vector<input_event> kStroke = {
    ev(1000, EV_ABS, ABS_X, 10000),
    ev(1000, EV_ABS, ABS_Y, 5000),
    ev(1000, EV_ABS, ABS_DISTANCE, 30),
    ev(1000, EV_KEY, BTN_TOOL_PEN, 1),
    ev(1000, EV_MSC, MSC_SERIAL, 0x0BADC0DE),
    ev(1000, EV_ABS, ABS_MISC, 0x802),
    ev(1000, EV_SYN, SYN_REPORT, 0),
    ev(2000, EV_ABS, ABS_X, 10200),
    ev(2000, EV_ABS, ABS_PRESSURE, 4096),
    ev(2000, EV_ABS, ABS_DISTANCE, 0),
    ev(2000, EV_ABS, ABS_TILT_X, 57),
    ev(2000, EV_ABS, ABS_TILT_Y, -57),
    ev(2000, EV_KEY, BTN_TOUCH, 1),
    ev(2000, EV_KEY, BTN_STYLUS, 1),
    ev(2000, EV_MSC, MSC_SERIAL, 0x0BADC0DE),
    ev(2000, EV_SYN, SYN_REPORT, 0),
    ev(3000, EV_ABS, ABS_X, 0),
    ev(3000, EV_ABS, ABS_Y, 0),
    ev(3000, EV_ABS, ABS_PRESSURE, 0),
    ev(3000, EV_KEY, BTN_TOUCH, 0),
    ev(3000, EV_KEY, BTN_STYLUS, 0),
    ev(3000, EV_KEY, BTN_TOOL_PEN, 0),
    ev(3000, EV_ABS, ABS_MISC, 0),
    ev(3000, EV_MSC, MSC_SERIAL, 0x0BADC0DE),
    ev(3000, EV_SYN, SYN_REPORT, 0),
};

TEST(EvdevPenState, OneSamplePerFrameWithUnits) {
  EvdevPenState state(pth660());
  std::vector<PenSample> s = feedAll(state, kStroke);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].t_ns, 1000000);
  EXPECT_TRUE(s[0].in_proximity);
  EXPECT_FALSE(s[0].tipDown());
  EXPECT_EQ(s[0].tool, PenTool::kPen);
  EXPECT_EQ(s[0].tool_id, 0x802u);
  EXPECT_EQ(s[0].tool_serial, 0x0BADC0DEu);
  EXPECT_DOUBLE_EQ(s[0].x_mm, 50.0);
  EXPECT_NEAR(s[0].distance, 30.0 / 63.0, 1e-6);

  EXPECT_EQ(s[1].buttons, kPenTip | kPenStylus1);
  EXPECT_NEAR(s[1].pressure, 4096.0 / 8191.0, 1e-6);
  EXPECT_DOUBLE_EQ(s[1].x_mm, 51.0);
  EXPECT_NEAR(s[1].tilt_x_deg, 57.0 / (57 * M_PI / 180.0), 1e-4);  // 57.3 degrees
  EXPECT_NEAR(s[1].tilt_y_deg, -57.2958, 1e-3);

  // The leaving frame: the stroke ends at the last position, not at the zeroed axes.
  EXPECT_FALSE(s[2].in_proximity);
  EXPECT_EQ(s[2].buttons, 0u);
  EXPECT_EQ(s[2].pressure_raw, 0);
  EXPECT_EQ(s[2].x_raw, 10200);
  EXPECT_EQ(s[2].tool_id, 0x802u);
  EXPECT_EQ(s[2].t_ns, 3000000);
}

TEST(EvdevPenState, EraserAndNoSamplesOutOfProximity) {
  EvdevPenState state(pth660());
  std::vector<PenSample> s =
      feedAll(state, {ev(1, EV_ABS, ABS_X, 5), ev(1, EV_SYN, SYN_REPORT, 0),
                      ev(2, EV_KEY, BTN_TOOL_RUBBER, 1), ev(2, EV_SYN, SYN_REPORT, 0)});
  ASSERT_EQ(s.size(), 1u) << "no sample while no tool is in proximity";
  EXPECT_EQ(s[0].tool, PenTool::kEraser);
  EXPECT_EQ(s[0].x_raw, 5) << "state before proximity is kept";
}

TEST(EvdevPenState, DisconnectMidStroke) {
  EvdevPenState state(pth660());
  std::vector<input_event> down(kStroke.begin(), kStroke.begin() + 16);
  ASSERT_EQ(feedAll(state, down).size(), 2u);
  PenSample out;
  ASSERT_TRUE(state.disconnect(99, out));
  EXPECT_FALSE(out.in_proximity);
  EXPECT_FALSE(out.tipDown());
  EXPECT_EQ(out.x_raw, 10200);
  EXPECT_FALSE(state.disconnect(100, out));
}

TEST(EvdevPenState, SynDroppedResyncEventsRebuildTheState) {
  // After SYN_DROPPED libevdev replays the device's state as ordinary events + SYN_REPORT.
  EvdevPenState state(pth660());
  feedAll(state, std::vector<input_event>(kStroke.begin(), kStroke.begin() + 7));
  std::vector<PenSample> s =
      feedAll(state, {ev(5, EV_ABS, ABS_X, 20000), ev(5, EV_ABS, ABS_PRESSURE, 100),
                      ev(5, EV_KEY, BTN_TOUCH, 1), ev(5, EV_SYN, SYN_REPORT, 0)});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].x_raw, 20000);
  EXPECT_EQ(s[0].y_raw, 5000);
  EXPECT_TRUE(s[0].tipDown());
}

}  // namespace
}  // namespace cb

namespace cb {
namespace {

TEST(EvdevPenState, ToolKeysAreTrackedSeparately) {
  // Seeding every tool key from the device state (pen down, pencil up) must not lose the pen.
  EvdevPenState state(pth660());
  state.setKey(BTN_TOOL_PEN, true);
  state.setKey(BTN_TOOL_PENCIL, false);
  state.setKey(BTN_TOOL_BRUSH, false);
  PenSample s;
  ASSERT_TRUE(state.feed(ev(1, EV_SYN, SYN_REPORT, 0), s));
  EXPECT_TRUE(s.in_proximity);
}

}  // namespace
}  // namespace cb
