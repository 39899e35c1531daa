// Outcome of feeding one raw report to a decoder.
#pragma once

#include <string>

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
};

}  // namespace cb::hid
