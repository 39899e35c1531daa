// A BIDS dataset of recorded study sessions (BIDS specification 1.9.0), for publishing a study
// in the layout neuroscience and psychology archives expect (`cloudbrush study export --bids`):
//
//   dataset_description.json, README
//   participants.tsv / .json      one row per participant: the study code, participant number
//                                 and every demographic answer (study.answer field=...)
//   sub-S/sub-S_sessions.tsv/.json  one row per session: acquisition time (UTC), folder id,
//                                 protocol, venue, operator, how it ended
//   sub-S/ses-T/beh/...task-cloudpainting_beh.tsv, _events.tsv + sidecars (bids_behaviour.h)
//   phenotype/questionnaire.tsv/.json, feedback.tsv/.json  the questionnaire answers, a row per
//                                 session, every question described (bids_phenotype.h; with a
//                                 protocol only)
//   sub-S/ses-T/motion/...task-cloudpainting_tracksys-tablet_motion.tsv, _channels.tsv,
//                                 _motion.json (bids_motion.h), and the events again (events
//                                 belong with the recording they time, in its own folder)
//   sourcedata/sub-S/ses-T/saved/  the clouds the participant saved in the session (the session
//                                 folder's saved/, byte for byte; sourcedata/ is BIDS's place for
//                                 files in their own formats)
//
// S is the participant's code with everything but ASCII letters and digits removed (P01 → P01;
// a journal without one: its session id), T the participant's session number, 1, 2, ... in the
// order the journals are given (so participants with one session each all have ses-1, as the
// validator expects; the session's folder id and UTC start are in the sessions.tsv). Every file
// goes through the atomic writer (app/core/atomic_file.h).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "app/study/bids_phenotype.h"
#include "app/study/protocol.h"
#include "app/study/session_trace.h"

namespace cb {

class BidsDatasetWriter {
 public:
  // `protocol` (may be null: no phenotype files) describes the questionnaires.
  explicit BidsDatasetWriter(std::string dir, const StudyProtocol* protocol = nullptr);

  // Writes one session's beh/ and motion/ files. False with *error naming the file.
  bool addSession(const SessionTrace& trace, std::string* error);
  // The dataset-level and subject-level files; call once after every session.
  bool finish(std::string* error);

  // Every file written so far, in order.
  const std::vector<std::string>& written() const { return written_; }

 private:
  struct SessionRow {
    std::string label, session_id, acq_time, protocol, protocol_version, venue, operator_initials,
        ended;
  };
  struct Subject {
    std::string participant, number;
    std::map<std::string, std::string> demographics;  // field id → answer
    std::vector<SessionRow> sessions;
  };
  bool write(const std::string& relative, const std::string& content, std::string* error);
  bool writeParticipants(std::string* error);
  bool writeSessions(const std::string& subject, const Subject& s, std::string* error);
  // The session folder's saved/ (the painter's Save in a study) into `to` (relative).
  bool copySaved(const SessionTrace& trace, const std::string& to, std::string* error);

  std::string dir_;
  const StudyProtocol* protocol_ = nullptr;
  std::vector<BidsPhenotypeRow> phenotype_;
  std::map<std::string, Subject> subjects_;  // by label
  std::string protocol_name_;
  std::vector<std::string> written_;
};

}  // namespace cb
