#include "app/study/session_outcome.h"

#include <algorithm>
#include <cstdlib>

#include "app/study/study_marker_text.h"

namespace cb {

SessionOutcome sessionOutcome(const SessionTrace& trace) {
  SessionOutcome o;
  int64_t last_ns = trace.t0_ns;
  for (const TraceEvent& e : trace.events) last_ns = std::max(last_ns, e.t_ns);
  if (!trace.samples.empty()) last_ns = std::max(last_ns, trace.samples.back().t_ns);
  for (const TraceEvent& e : trace.events) {
    if (e.type != JournalRecordType::kMarker || e.text.rfind("study.", 0) != 0) continue;
    const StudyMarkerFields m = parseStudyMarker(e.text);
    if (m.event == "study.session" && !o.start_ns) {
      o.start_ns = e.t_ns;
      o.status = "unfinished";
    } else if (m.event == "study.resume") {
      o.down_ns += std::max<int64_t>(0, std::strtoll(m.get("down_ns").c_str(), nullptr, 10));
    } else if (m.event == "study.end" && !o.end_ns) {
      o.end_ns = e.t_ns;
      const std::string how = m.words.empty() ? "" : m.words[0];
      o.status = how == "completed" || how == "aborted" || how == "declined" ? how : "unfinished";
      o.reason = m.get("reason");
    }
  }
  // A journal that is not a study session: its own first to last record.
  const int64_t start = o.start_ns.value_or(trace.t0_ns), end = o.end_ns.value_or(last_ns);
  o.duration_s = double(std::max<int64_t>(0, elapsedNs(end, start) - o.down_ns)) * 1e-9;
  return o;
}

}  // namespace cb
