// The kiosk's bundled attract journal (config/kiosk/attract.cbj): a short painting session made
// from synthetic pen strokes (app/session/synthetic_session.h) — a flat base and three puffs of a
// cumulus — recorded by a PaintSession exactly as a visitor's would be, so the attract loop
// replays it like any recorded session. Deterministic: the same bytes on every run.
// Regenerate with:  cloudbrush kiosk --make-attract-journal config/kiosk/attract.cbj
#pragma once

#include <string>

namespace cb {

// False with *error naming the file when it cannot be written.
bool writeAttractJournal(const std::string& path, std::string* error);

}  // namespace cb
