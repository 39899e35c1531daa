// Which of the study runner's journal markers (study_run_state.h) other recorders hear as sync
// markers (drivers/core/JOURNAL.md section 10), and under which kind. The label is the marker's
// text after its event word ("stage=task task=cloud1 position=1 ...").
//   study.session        session_start
//   study.stage-begin    task_begin (a task) or stage_begin
//   study.stage-closing  task_end (a task: the participant stops painting — time up, done,
//                        skipped — before its files are saved) or stage_closing
//   study.stage-end      stage_end (after a task's files are saved)
//   study.consent        consent
//   study.answer         answer
//   study.operator       operator (pause, resume, skip, abort)
//   study.end            session_end
// Other markers (saved files, tutorial steps, requests) are not sent.
#pragma once

#include <optional>
#include <string>

namespace cb {

struct StudySyncMarker {
  std::string kind, label;
};

std::optional<StudySyncMarker> studySyncMarker(const std::string& record_text);

}  // namespace cb
