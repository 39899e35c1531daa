// The pen motion every in-the-loop test injects (hover, touch, pressure ramp, tilt sweep,
// buttons, eraser, proximity out), the reports that carry it for a descriptor-described pen
// (PTH-660) and for the Intuos4 protocol, and the PenSamples it must come out as.
#pragma once

#include <cstdint>
#include <vector>

#include "drivers/core/pen_sample.h"
#include "drivers/hid/hid_pen_layout.h"
#include "drivers/hid/pen_report_encoder.h"

namespace cb::hil {

using PenStep = hid::PenReportState;
using hid::encodeIntuos4Enter;
using hid::encodeIntuos4Exit;
using hid::encodeIntuos4Pen;
using hid::encodePenReport;

// Steps spanning the full ranges of a pen with the given maxima.
// The eraser end the script uses (a Wacom Intuos4 pen's eraser, 0x80a); the decoders must
// classify it from the device files' tool table.
inline constexpr uint32_t kScriptEraserToolId = 0x80A;

std::vector<PenStep> penScript(int32_t x_max, int32_t y_max, int32_t pressure_max,
                               int32_t distance_max);

// What a backend must report for a step, computed from the script (not from a decoder):
// returns false when the step yields no sample (pen stays out of proximity).
bool expectedSample(const PenStep& step, const PenDeviceInfo& info, bool intuos4,
                    PenSample& previous, PenSample& out);

}  // namespace cb::hil
