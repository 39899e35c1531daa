// Resuming a session from its own journal ("restarting on the same session folder
// resumes it"). The journal at `path` is re-opened for appending after its last whole record (a
// torn tail from a crash is cut, with a warning), replayed into a fresh PaintSession with the
// journal's own session settings and recorded configuration, and the session carries on
// recording into the same file from the last durable record. A path that holds nothing yet (or
// a journal cut before its first record) starts a new session there; a file that holds
// something else (a pen recording without a session, not a journal at all) is refused and left
// alone.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "drivers/core/journal.h"

namespace cb {

struct ResumedSession {
  std::unique_ptr<PaintSession> session;
  bool resumed = false;         // false: the file held no session; a new one was started
  SessionReplay replay;         // what the replay rebuilt (session moved out into `session`)
  std::string warning;          // a torn tail that was cut, or records that did not apply
  int64_t last_sample_ns = -1;  // t_ns of the journal's last pen sample (-1: none)
};

// `settings`, `brush` and `mapping` make a new session (and are the fallback for a journal
// without recorded settings). A journal recorded on another screen size or grid is refused (its
// pen would map differently), and so is a file that holds no painting session. On success `journal`
// is open on `path`; a resumed session already records into it, a new one (resumed == false) is not
// recording yet: the caller sets its starting state (light, style, an opened cloud) and calls
// recordTo(journal, t). False with *error (naming the file) leaves the file as it was.
bool resumeOrStartSession(const std::string& path, const PaintSessionSettings& settings,
                          const BrushConfig& brush, const MappingConfig& mapping,
                          JournalWriter* journal, ResumedSession* out, std::string* error);

}  // namespace cb
