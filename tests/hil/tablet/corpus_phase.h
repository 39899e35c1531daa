// The `corpus` phase of the virtual tablet test: every non-Wacom pen of the corpus
// (tests/fixtures/hid/pen_corpus_reports.txt) is created over uhid, the kernel binds
// hid-generic (hid-input's rules), and its scripted motion is compared step by step on evdev
// and on our hidraw decode, against the script and against each other, field by field. hid-input
// sets no fuzz on these axes (input_set_abs_params(..., 0, 0)), so no difference is allowed.
#pragma once

#include <string>

namespace cb::hil {

// Runs the phase, printing "CB-HIL CHECK" and "CB-HIL FIGURE" lines; returns failed checks.
int runCorpusPhase(const std::string& fixture_dir);

}  // namespace cb::hil
