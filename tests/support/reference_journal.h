// A recorded painting session for the crash and power-cut tests: the reference strokes of
// app/session/synthetic_session.h, `rounds` times over 0.3 s apart, fed at 200 Hz through a real
// PaintSession that journals them (Session, Settings, Device, samples, StrokeMapped records).
#pragma once

#include <string>

namespace cb::test {

// Writes the journal to `path` on a width × height screen with a 16³ grid. False with *error
// when the journal cannot be opened.
bool recordReferenceJournal(const std::string& path, int width, int height, int rounds,
                            std::string* error);

}  // namespace cb::test
