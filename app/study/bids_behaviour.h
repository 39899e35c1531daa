// The behavioural files of one study session in a BIDS dataset (BIDS specification 1.9,
// "Behavioral experiments (with no neural recordings)" and "Task events"), read from the
// runner's markers in the journal (drivers/core/JOURNAL.md section 7):
//
//   _beh.tsv     one row per trial (a task the participant painted): trials.csv's columns
//                (trial_table.h), missing values n/a
//   _events.tsv  onset, duration, trial_type, ...: every stage of the session (consent to
//                questionnaire; a task's row carries its trial's figures) and every operator
//                pause, sorted by onset
//
// Times are seconds after the journal's first record, the time origin of the session's pen
// motion recording too (bids_motion.h), so events and pen samples share one clock. Each TSV has
// a JSON sidecar describing every column with its units and levels.
#pragma once

#include <string>

#include "app/study/session_trace.h"

namespace cb {

std::string bidsBehTsv(const SessionTrace& trace);
std::string bidsBehJson();
std::string bidsEventsTsv(const SessionTrace& trace);
std::string bidsEventsJson();

}  // namespace cb
