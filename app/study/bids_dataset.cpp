#include "app/study/bids_dataset.h"

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <system_error>

#include "app/core/atomic_file.h"
#include "app/core/json_text.h"
#include "app/study/bids_behaviour.h"
#include "app/study/bids_motion.h"
#include "app/study/bids_text.h"
#include "app/study/saved_clouds.h"
#include "app/study/study_marker_text.h"
#include "app/study/study_session_record.h"

namespace cb {
namespace {

const char kTaskLabel[] = "cloudpainting";
const char kTaskName[] = "cloud painting";
const char kTaskDescription[] =
    "A study session on the cloudbrush kiosk: consent, the participant's code, an introduction, "
    "a guided tutorial, free drawing, then painting tasks in a counterbalanced order (paint a "
    "volumetric cloud like a reference picture with a pen on a tablet, within a time limit), "
    "demographic questions and a Likert questionnaire";

const char kReadme[] =
    "Study sessions recorded with cloudbrush, a kiosk on which a person paints volumetric\n"
    "clouds with a pen tablet, exported from the session journals by\n"
    "`cloudbrush study export --bids`.\n\n"
    "Each session (sub-<participant>/ses-<the participant's session number>) holds:\n"
    "- beh/*_beh.tsv: one row per painting task (trial): order, onset, duration on the stage\n"
    "  clock (operator pauses not counted), how it ended, strokes, erases, undos.\n"
    "- beh/*_events.tsv: every stage of the session and every operator pause (onset,\n"
    "  duration, trial_type); task rows carry their trial's figures.\n"
    "- motion/*_tracksys-tablet_motion.tsv: every raw pen report (position in mm, tilt in\n"
    "  degrees, pressure, hover distance, contact, buttons, tool), its time in the LATENCY\n"
    "  channel because the tablet reports when the pen moves, not at a fixed rate;\n"
    "  *_channels.tsv describes each column. The events are repeated beside the recording.\n\n"
    "All times are seconds after the session journal's first record. participants.tsv holds\n"
    "the demographic answers; sub-*/sub-*_sessions.tsv the UTC start, protocol, venue and\n"
    "operator of each session. phenotype/questionnaire.tsv holds the Likert answers (a row\n"
    "per session; n/a: skipped or never reached) and phenotype/feedback.tsv the free-text\n"
    "comments; their JSON sidecars give each question in English and Chinese, its scale\n"
    "and the constructs it belongs to.\n";

struct SessionFacts {
  std::string number, protocol, protocol_version, venue, operator_initials, ended;
  std::optional<int64_t> start_unix_ns;
  std::map<std::string, std::string> demographics;
};

SessionFacts sessionFacts(const SessionTrace& trace) {
  SessionFacts f;
  for (const TraceEvent& e : trace.events) {
    if (e.type != JournalRecordType::kMarker || e.text.rfind("study.", 0) != 0) continue;
    StudySessionInfo info;
    if (!f.start_unix_ns && parseStudyInfoMarker(e.text, &info)) {
      f.number = std::to_string(info.participant_number);
      f.protocol = info.protocol_name;
      f.protocol_version = info.protocol_version;
      f.venue = info.venue;
      f.operator_initials = info.operator_initials;
      if (info.anchor_unix_ns != 0)
        f.start_unix_ns = info.anchor_unix_ns + (trace.t0_ns - info.anchor_monotonic_ns);
      continue;
    }
    const StudyMarkerFields m = parseStudyMarker(e.text);
    if (m.event == "study.answer" && m.has("field"))
      f.demographics[m.get("field")] = m.isNa("value") ? "" : m.get("value");
    else if (m.event == "study.end")
      f.ended = m.words.empty() ? "other" : m.words[0];
  }
  return f;
}

// "2026-11-22T10:00:00.123456Z" (BIDS acq_time, UTC).
std::string acqTime(int64_t unix_ns) {
  const int64_t seconds =
      unix_ns >= 0 ? unix_ns / 1'000'000'000 : (unix_ns + 1) / 1'000'000'000 - 1;
  const int64_t micros = (unix_ns - seconds * 1'000'000'000) / 1000;
  const std::time_t t = std::time_t(seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[48];
  const size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  std::snprintf(text + n, sizeof text - n, ".%06lldZ", static_cast<long long>(micros));
  return text;
}

const std::vector<BidsColumn>& sessionColumns() {
  static const std::vector<BidsColumn> columns = {
      {"session_id", "The session's BIDS label", "", {}},
      {"acq_time", "When the session's recording began, UTC", "", {}},
      {"session", "The session's id in the study: its folder's name", "", {}},
      {"protocol", "The study protocol's name", "", {}},
      {"protocol_version", "The study protocol's version", "", {}},
      {"venue", "Where the session ran (the protocol's venue id)", "", {}},
      {"operator", "The operator's initials", "", {}},
      {"ended",
       "How the session ended; n/a when the recording stops before its end",
       "",
       {{"completed", "every stage was run"},
        {"aborted", "the operator aborted the session (reason in the journal)"},
        {"other", "another ending the runner recorded"}}}};
  return columns;
}

}  // namespace

BidsDatasetWriter::BidsDatasetWriter(std::string dir, const StudyProtocol* protocol)
    : dir_(std::move(dir)), protocol_(protocol) {}

bool BidsDatasetWriter::write(const std::string& relative, const std::string& content,
                              std::string* error) {
  const std::filesystem::path path = std::filesystem::path(dir_) / relative;
  const std::filesystem::path folder = path.parent_path();
  if (!std::filesystem::is_directory(folder)) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) return *error = folder.string() + ": cannot create the folder: " + ec.message(), false;
    // The new folder's entry in its parent must reach the disk too.
    if (!syncFolderOf(folder.string(), error)) return false;
  }
  if (!writeFileAtomically(path.string(), content, error)) return false;
  written_.push_back(path.string());
  return true;
}

bool BidsDatasetWriter::copySaved(const SessionTrace& trace, const std::string& to,
                                  std::string* error) {
  // The clouds the participant saved with the painter's Save (saved_clouds.h: the one copy
  // `study export --out` makes too).
  return copySavedClouds(trace.path, (std::filesystem::path(dir_) / to).string(), &written_, error);
}

bool BidsDatasetWriter::addSession(const SessionTrace& trace, std::string* error) {
  const SessionFacts facts = sessionFacts(trace);
  const std::string subject = bidsLabel(trace.participant.empty() ? trace.id : trace.participant);
  if (subject.empty())
    return *error = trace.path + ": no letters or digits in the id '" + trace.id +
                    "' to name a BIDS subject",
           false;
  Subject& s = subjects_[subject];
  const std::string session = std::to_string(s.sessions.size() + 1);
  if (s.participant.empty()) {
    s.participant = trace.participant;
    s.number = facts.number;
  }
  for (const auto& [field, answer] : facts.demographics) s.demographics.emplace(field, answer);
  if (protocol_name_.empty()) protocol_name_ = facts.protocol;
  s.sessions.push_back({session, trace.id, facts.start_unix_ns ? acqTime(*facts.start_unix_ns) : "",
                        facts.protocol, facts.protocol_version, facts.venue,
                        facts.operator_initials, facts.ended});

  BidsPhenotypeRow answers = phenotypeAnswers(trace);
  answers.participant_id = "sub-" + subject;
  answers.session_id = "ses-" + session;
  phenotype_.push_back(std::move(answers));

  const std::string folder = "sub-" + subject + "/ses-" + session + "/";
  const std::string base = "sub-" + subject + "_ses-" + session + "_task-" + kTaskLabel;
  const std::string events = bidsEventsTsv(trace), events_json = bidsEventsJson();
  if (!write(folder + "beh/" + base + "_beh.tsv", bidsBehTsv(trace), error) ||
      !write(folder + "beh/" + base + "_beh.json", bidsBehJson(), error) ||
      !write(folder + "beh/" + base + "_events.tsv", events, error) ||
      !write(folder + "beh/" + base + "_events.json", events_json, error) ||
      !copySaved(trace, "sourcedata/" + folder + "saved/", error))
    return false;
  if (trace.samples.size() < 2) return true;  // no pen trace to speak of
  const std::string motion = folder + "motion/" + base;
  return write(motion + "_tracksys-tablet_motion.tsv", bidsMotionTsv(trace), error) &&
         write(motion + "_tracksys-tablet_motion.json",
               bidsMotionJson(trace, kTaskName, kTaskDescription), error) &&
         write(motion + "_tracksys-tablet_channels.tsv", bidsChannelsTsv(), error) &&
         write(motion + "_events.tsv", events, error) &&
         write(motion + "_events.json", events_json, error);
}

bool BidsDatasetWriter::writeSessions(const std::string& subject, const Subject& s,
                                      std::string* error) {
  std::string tsv = bidsTsvHeader(sessionColumns());
  for (const SessionRow& r : s.sessions)
    tsv += "ses-" + r.label + '\t' + bidsTsvText(r.acq_time) + '\t' + bidsTsvText(r.session_id) +
           '\t' + bidsTsvText(r.protocol) + '\t' + bidsTsvText(r.protocol_version) + '\t' +
           bidsTsvText(r.venue) + '\t' + bidsTsvText(r.operator_initials) + '\t' +
           bidsTsvText(r.ended) + '\n';
  const std::string base = "sub-" + subject + "/sub-" + subject + "_sessions";
  return write(base + ".tsv", tsv, error) &&
         write(base + ".json", bidsColumnsJson(sessionColumns()), error);
}

bool BidsDatasetWriter::writeParticipants(std::string* error) {
  std::vector<BidsColumn> columns = {
      {"participant_id", "The participant's BIDS label", "", {}},
      {"participant", "The participant's pseudonymous code in the study", "", {}},
      {"number", "The participant's number in the study (sets the task order)", "", {}}};
  std::map<std::string, bool> fields;
  for (const auto& [label, s] : subjects_)
    for (const auto& [field, answer] : s.demographics) fields[field] = true;
  for (const auto& [field, unused] : fields)
    columns.push_back(
        {field,
         "The answer to the protocol's demographic question '" + field + "' (n/a: not answered)",
         "",
         {}});
  std::string tsv = bidsTsvHeader(columns);
  for (const auto& [label, s] : subjects_) {
    tsv += "sub-" + label + '\t' + bidsTsvText(s.participant) + '\t' + bidsTsvText(s.number);
    for (const auto& [field, unused] : fields) {
      const auto answer = s.demographics.find(field);
      tsv += '\t' + bidsTsvText(answer == s.demographics.end() ? "" : answer->second);
    }
    tsv += '\n';
  }
  return write("participants.tsv", tsv, error) &&
         write("participants.json", bidsColumnsJson(columns), error);
}

bool BidsDatasetWriter::finish(std::string* error) {
  const std::string name =
      "cloudbrush study" + (protocol_name_.empty() ? std::string() : ": " + protocol_name_);
  const std::string description = bidsJsonObject(
      {{"Name", jsonString(name)},
       {"BIDSVersion", "\"1.9.0\""},
       {"DatasetType", "\"raw\""},
       {"GeneratedBy",
        "[{\"Name\": \"cloudbrush\", \"Version\": " + jsonString(cloudbrushVersion()) +
            ", \"Description\": \"cloudbrush study export --bids, from the "
            "session journals\"}]"}});
  if (!write("dataset_description.json", description, error) || !write("README", kReadme, error) ||
      !writeParticipants(error))
    return false;
  for (const auto& [label, s] : subjects_)
    if (!writeSessions(label, s, error)) return false;
  if (protocol_)
    for (const auto& [path, content] : bidsPhenotypeFiles(*protocol_, phenotype_))
      if (!write(path, content, error)) return false;
  return true;
}

}  // namespace cb
