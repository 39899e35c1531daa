// How a study session went, from its journal's own `study.*` markers (drivers/core/JOURNAL.md
// section 7), for the report: how it ended and how long it ran on the session's clock.
//
//   status     completed | aborted (the operator) | declined (no consent) | unfinished (the
//              journal ends before `study.end`: a session still running or lost) | not-a-study
//              (no `study.session` marker: a plain painting journal)
//   start      the `study.session` marker (the runner's state machine starts)
//   end        the `study.end` marker, else the journal's last record
//   duration   end − start (a journal that is not a study session: its first to last record) on the
//   journal's monotonic clock, less the time a restarted runner was
//              down (Σ `study.resume down_ns`: the clock jumps over it when the machine did not
//              reboot). Pen samples play no part: a session spends much of its time on pages
//              where the pen only taps.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "app/study/session_trace.h"

namespace cb {

struct SessionOutcome {
  std::string status = "not-a-study";
  std::string reason;  // the operator's reason for an abort, else ""
  std::optional<int64_t> start_ns, end_ns;
  int64_t down_ns = 0;
  double duration_s = 0;
  // Only completed sessions count as participants in the questionnaire's statistics.
  bool counts() const { return status == "completed"; }
};

SessionOutcome sessionOutcome(const SessionTrace& trace);

}  // namespace cb
