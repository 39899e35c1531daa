// Outcome of feeding one raw report to a decoder.
#pragma once

#include <optional>
#include <string>

#include "drivers/core/pen_sample.h"

namespace cb::hid {

enum class DecodeStatus {
  kSample,       // a PenSample was produced
  kNoSample,     // a valid report that changes state only (tool enter, hover out of sense, ...)
  kOtherReport,  // a report this decoder does not handle (pad, touch, other report ID)
  kRejected,     // malformed: wrong length; `reason` says what and by how much
};

struct DecodeResult {
  DecodeStatus status = DecodeStatus::kNoSample;
  std::string reason;
  // Set when the kernel would release the tool in the middle of this report and send an extra
  // EV_SYN (hid-input's hid_report_release_tool, e.g. rubber -> pen while in range): evdev then
  // shows this proximity-out sample before the report's own sample.
  std::optional<PenSample> released;
};

}  // namespace cb::hid
