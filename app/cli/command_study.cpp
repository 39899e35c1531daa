// cloudbrush study: exports and the questionnaire report for user studies, built on
// app/study. `study export` writes pen traces (and, with --volumes, replayed volumes and renders)
// of one or many sessions; `study volume` exports a saved volume; `study report` writes the
// offline HTML report of questionnaire answers; `study check` validates a study protocol;
// `study withdraw` deletes one participant's data.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "app/brush/brush_config.h"
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/study_bids_export.h"
#include "app/cli/study_export_files.h"
#include "app/cli/study_frame_render.h"
#include "app/cli/study_trace_export.h"
#include "app/core/atomic_file.h"
#include "app/core/config_paths.h"
#include "app/mapping/mapping_config.h"
#include "app/render/gl/display.h"
#include "app/render/render_config.h"
#include "app/render/volume_renderer.h"
#include "app/session/paint_session.h"
#include "app/session/session_replay.h"
#include "app/session/session_resume.h"
#include "app/session/sync_marker_sender.h"
#include "app/shell/frame_loop.h"
#include "app/shell/keymap.h"
#include "app/shell/study/study_run_screen.h"
#include "app/study/codebook.h"
#include "app/study/construct_definitions.h"
#include "app/study/inkml_writer.h"
#include "app/study/journal_answers.h"
#include "app/study/likert_answers.h"
#include "app/study/participant_withdrawal.h"
#include "app/study/protocol.h"
#include "app/study/protocol_summary.h"
#include "app/study/render_export.h"
#include "app/study/session_trace.h"
#include "app/study/study_report.h"
#include "app/study/study_report_html.h"
#include "app/study/study_run_state.h"
#include "app/study/study_session_record.h"
#include "app/study/trace_csv.h"
#include "app/study/trial_table.h"
#include "app/study/volume_export.h"
#include "app/volume/volume_file.h"
#include "drivers/core/clock.h"
#include "drivers/open_pen_source.h"
#include "drivers/replay/replay_pen_source.h"

namespace cb {
namespace {

const char kStudyHelp[] =
    "usage: cloudbrush study export SESSION.cbj... --out DIR [--volumes] [--size WxH]\n"
    "                               [--bids DIR]\n"
    "                               [--protocol FILE.toml]\n"
    "       cloudbrush study export --manifest FILE --out DIR [--shard I/N | --merge] ...\n"
    "       cloudbrush study volume VOLUME.cbvol --out DIR [--render] [--size WxH]\n"
    "       cloudbrush study report [ANSWERS.csv] [SESSION.cbj...] --out REPORT.html\n"
    "                               [--constructs FILE.toml | --protocol FILE.toml]\n"
    "                               [--pair Q3,Q6] [--title TEXT]\n"
    "       cloudbrush study check [PROTOCOL.toml] [--vocabulary]\n"
    "       cloudbrush study withdraw --data DIR --participant ID [--key-file FILE] [--dry-run]\n"
    "       cloudbrush study run [PROTOCOL.toml] [--data-dir DIR] [--participant N] [--venue ID]\n"
    "                            [--operator INITIALS] [--display auto|kms|x11|surfaceless]\n"
    "                            [--size WxH] [--grid N] [--backend NAME] [--pen-device PATH]\n"
    "                            [--journal FILE] [--keys LIST] [--frames N] [--seconds S]\n"
    "                            [--sync-udp [HOST:]PORT]  (task and stroke boundaries as UDP)\n"
    "                            [--resume FOLDER] [--end-seconds S]\n"
    "\n"
    "export   pen traces of one session or a whole study, one file per kind (sessions\n"
    "         concatenated in the order given, each row or trace group tagged with the\n"
    "         session id, the journal's file name without extension):\n"
    "           DIR/traces.inkml  W3C InkML, channels X Y (mm) F (device units) OTx OTy (deg)\n"
    "                             T (ms), the capture device in each context's inkSource\n"
    "           DIR/samples.csv   every raw pen sample\n"
    "           DIR/strokes.csv   per stroke: start, duration, path length, mean/max pressure,\n"
    "                             mean tilt, speed, brush, mode, mapping time (NA: not recorded)\n"
    "           DIR/events.csv    every UI/mode change, marker, calibration, session record\n"
    "           DIR/trials.csv    one row per study task: order, onset, duration, end reason\n"
    "           DIR/saved/ID/     the clouds the participant saved with the painter's Save\n"
    "                             (the session folder's saved/, byte for byte; --bids puts\n"
    "                             the same files in sourcedata/)\n"
    "           DIR/codebook.csv  every variable of these files and of questionnaire.csv and\n"
    "                             demographics.csv: type, unit, meaning; each item's text in\n"
    "                             English and Chinese, scale and anchors, construct, section\n"
    "                             (items of --protocol FILE, else of the protocol the first\n"
    "                             study session names, else of the bundled one)\n"
    "         --volumes replays each journal (brush and mapping from the config directory) and\n"
    "         writes DIR/volumes/ID.vdb and ID.cbvol and DIR/renders/ID.exr (linear light) and\n"
    "         ID.png from the session's last view, at --size (default 1280x720).\n"
    "         --bids DIR writes the sessions as a BIDS dataset (--out then optional): per\n"
    "         participant and session beh/ (trials, events) and motion/ (the pen trace),\n"
    "         participants.tsv, sidecars describing every column (app/study/bids_dataset.h).\n"
    "         --manifest FILE: the journals, one per line (# comments; relative to FILE's\n"
    "         folder) instead of as arguments. --shard I/N exports only the I-th of N\n"
    "         contiguous blocks of them (volumes and renders into DIR, the trace rows as\n"
    "         parts under DIR/shards/I-of-N), for a job array (docs/study-on-slurm.md);\n"
    "         --merge then joins every shard's parts into DIR's files, byte for byte what\n"
    "         one run over the whole manifest writes, and removes DIR/shards.\n"
    "volume   a saved volume as OUT/NAME.vdb (OpenVDB fog volume, grid 'density') and\n"
    "         OUT/NAME.cbvol; --render adds OUT/NAME.exr and NAME.png from the reference camera.\n"
    "report   an HTML page that opens offline: Likert distributions per item (NA where nobody\n"
    "         answered), construct summaries (every construct of the protocol: --protocol\n"
    "         FILE, else the one the first session names, else the bundled one; or\n"
    "         --constructs FILE.toml, see app/study/construct_definitions.h), the paired\n"
    "         one-tailed t-test of --pair (default Q3,Q6: the 2D vs 3D brush ratings, thesis\n"
    "         §7.7.2); when journals are given, per-task times from their trials and per\n"
    "         session its status, duration on the session's clock, pressure and stroke speed\n"
    "         (median, IQR, outliers named). Participants whose sessions were aborted,\n"
    "         declined or unfinished, and those who answered nothing, are set apart, not\n"
    "         counted. The answers come from the journals' study.answer records when\n"
    "         sessions are given (ANSWERS.csv, an export, is then only compared with them,\n"
    "         each difference said), else from ANSWERS.csv: participant,Q1,...,Qn with\n"
    "         answers 1..5 or NA.\n"
    "check    reads a study protocol (default: the bundled config/study/thesis_2014.toml;\n"
    "         format: app/study/protocol.h) and prints a summary: stages, tutorial steps and\n"
    "         their checks, tasks, the task order of each participant over one cycle, the\n"
    "         questionnaire and constructs. An error exits 1 naming FILE:LINE: FIELD; images or\n"
    "         videos it names that do not exist exit 3. --vocabulary lists what tutorial checks\n"
    "         may name.\n"
    "withdraw deletes everything of participant ID under DIR: files and folders named ID or\n"
    "         ID_*, ID-*, ID.* (session folders), the rows of every CSV whose participant column\n"
    "         is ID or whose session column is such a name, and the ID's row in --key-file. Says\n"
    "         what it deleted, and which remaining files still mention ID (exit 3). An ID that\n"
    "         matches nothing is refused (exit 1). --dry-run only says what it would delete.\n"
    "run      runs a session of the protocol (default: the bundled thesis study) on the display,\n"
    "         driven by the pen: consent (tap \"I agree\"), the participant's code, the\n"
    "         introduction, the guided tutorial (each step moves on when its check holds), free\n"
    "         drawing, the tasks in the participant's counterbalanced order (reference picture\n"
    "         beside the canvas, a countdown; the task's files saved when it ends), demographics\n"
    "         and free text on an on-screen keyboard, the Likert questionnaire (tap one of five\n"
    "         boxes per item). The operator pauses/resumes with Ctrl+Alt+P, skips with\n"
    "         Ctrl+Alt+S and aborts with Ctrl+Alt+A, each with a reason (tap or digit key).\n"
    "         A protocol with an error is refused (exit 1, FILE:LINE: FIELD) and missing\n"
    "         pictures exit 3, before any screen opens. The session folder\n"
    "         DIR/ID-YYYYmmddTHHMMSSZ (DIR: --data-dir, default <state dir>/study) holds\n"
    "         session.json, session.cbj (the journal, stages as markers), questionnaire.csv,\n"
    "         demographics.csv, tasks/TASK.{vdb,cbvol,exr,png} and saved/ (the painter's\n"
    "         Save during the session: withdrawn with it); its path is printed first.\n"
    "         --participant N (N >= 1; 1 is the first id, P01) picks participant N (id and\n"
    "         task order); a participant with a session folder in DIR already is refused,\n"
    "         naming the folder (carry it on with --resume FOLDER; --resume with a new\n"
    "         FOLDER starts the session there as asked). Without --participant:\n"
    "         the first number whose id has no folder in DIR. --venue is required when the\n"
    "         protocol names more than one, --operator when it requires one.\n"
    "         Consent offers \"I agree\" and \"I do not agree\"; declining ends the session\n"
    "         there (session.json status \"declined\", no task data; exit 0). In a task the\n"
    "         participant may tap \"I'm done\" (confirmed by a second tap): the task ends\n"
    "         with the end reason `done` (trials.csv).\n"
    "         --resume FOLDER runs the session in FOLDER; when its journal already holds one (a\n"
    "         crash, a power cut), it is carried on: the journal is replayed (the cloud, the\n"
    "         stage, the tutorial step and its counters, the painter's menu, the answers, the\n"
    "         operator's pause, the stage clock, which does not count the time the runner was\n"
    "         down) and recording goes on after\n"
    "         its last whole record; protocol, participant, venue and operator are the\n"
    "         session's own. Use the same --size and --grid. With --backend replay the\n"
    "         session's clock is the recording's time line, and a resumed run's pen carries on\n"
    "         after the last sample the journal holds. --end-seconds: how long the closing\n"
    "         page shows (default 8).\n";

int fail(const std::string& message, int code = 1) {
  return studyFail(message, code);
}

// The journals `study export` is given: its arguments, or the lines of --manifest FILE.
int exportJournals(Args& args, std::vector<std::string>* paths) {
  const std::vector<std::string>& positional = args.positional();
  const std::string manifest = args.get("manifest", "");
  if (!manifest.empty()) {
    if (positional.size() > 2)
      return fail("export: give the journals as arguments or in --manifest FILE, not both", 2);
    try {
      *paths = readExportManifest(manifest);
    } catch (const StudyInputError& e) {
      return fail(e.what());
    }
    return 0;
  }
  if (positional.size() < 3)
    return fail(
        "export: expected one or more journals: study export SESSION.cbj... --out DIR "
        "(or --manifest FILE)",
        2);
  paths->assign(positional.begin() + 2, positional.end());
  for (const std::string& path : *paths)
    if (!std::filesystem::exists(path)) return fail("journal '" + path + "' does not exist");
  return 0;
}

int runExport(Args& args) {
  auto unknown = args.unknown(
      {"help", "out", "volumes", "size", "bids", "protocol", "manifest", "shard", "merge"});
  if (!unknown.empty()) return fail("export: unknown option " + unknown[0] + " (see --help)", 2);
  TraceExportRequest request;
  if (const int status = exportJournals(args, &request.journals)) return status;
  request.out = args.get("out", "");
  const std::string bids = args.get("bids", "");
  if (request.out.empty() && bids.empty())
    return fail("export: --out DIR (or --bids DIR) is required", 2);
  if (!parseStudySize(args.get("size", "1280x720"), &request.width, &request.height))
    return fail("export: --size: expected WxH (1..16384 each)", 2);
  const bool merge = args.has("merge");
  if (args.has("shard")) {
    ShardSpec spec;
    std::string error;
    if (!parseShardSpec(args.get("shard", ""), &spec, &error)) return fail("export: " + error, 2);
    request.shard = spec;
  }
  if ((request.shard || merge) &&
      (request.out.empty() || !bids.empty() || (request.shard && merge)))
    return fail(
        "export: --shard I/N and --merge take --out DIR, one at a time, and no --bids "
        "(a BIDS dataset is written from the whole manifest in one run)",
        2);
  for (const std::string& path : request.journals) {
    request.ids.push_back(sessionIdForJournal(path));
    for (size_t k = 0; k + 1 < request.ids.size(); ++k)
      if (request.ids[k] == request.ids.back())
        return fail("two journals have the session id '" + request.ids.back() + "' (" +
                    request.journals[k] + ", " + path + "); rename one");
  }
  if (!bids.empty()) {
    const int status =
        exportBidsDataset(request.journals, request.ids, bids, args.get("protocol", ""));
    if (status == 1 || request.out.empty()) return status;
  }
  request.volumes = args.has("volumes");
  request.protocol = args.get("protocol", "");
  return merge ? mergeStudyTraceShards(request) : exportStudyTraces(request);
}

int runVolume(Args& args) {
  auto unknown = args.unknown({"help", "out", "render", "size"});
  if (!unknown.empty()) return fail("volume: unknown option " + unknown[0] + " (see --help)", 2);
  if (args.positional().size() != 3)
    return fail("volume: expected one volume file: study volume VOLUME.cbvol --out DIR", 2);
  const std::string out = args.get("out", "");
  if (out.empty()) return fail("volume: --out DIR is required", 2);
  int width = 1280, height = 720;
  if (!parseStudySize(args.get("size", "1280x720"), &width, &height))
    return fail("volume: --size: expected WxH (1..16384 each)", 2);
  const std::string& path = args.positional()[2];
  Volume volume(glm::ivec3(1));
  try {
    volume = loadVolume(path);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return exportVolumeAndRender(volume, Camera::reference(), nullptr, out, out,
                               std::filesystem::path(path).stem().string(), args.has("render"),
                               width, height);
}

// The report's constructs: a --constructs file, else every construct of the study protocol
// (--protocol, else the one the first session names, else the bundled one). Throws on bad input.
std::string reportProtocolPath(Args& args, const std::vector<SessionTrace>& sessions) {
  std::string path = args.get("protocol", "");
  if (path.empty() && !sessions.empty()) path = protocolFileOf(sessions.front());
  return path.empty() ? defaultStudyProtocolPath() : path;
}

void chooseReportConstructs(Args& args, const std::vector<SessionTrace>& sessions,
                            StudyReportOptions* options) {
  if (args.has("constructs")) {
    options->constructs = loadConstructDefinitions(*args.get("constructs"));
    options->constructs_source = "Constructs declared in " + *args.get("constructs");
    return;
  }
  const std::string path = reportProtocolPath(args, sessions);
  const StudyProtocol protocol = loadStudyProtocol(path);
  for (const ProtocolConstruct& c : protocol.constructs)
    options->constructs.push_back({c.name, c.items});
  options->constructs_source = "Constructs of the study protocol " + path;
}

// The report's answers: the journals' `study.answer` markers over the protocol's items when
// sessions are given (a CSV given too is compared with them, each difference said), else the
// CSV. Throws on bad input.
LikertAnswers reportAnswers(Args& args, const std::vector<SessionTrace>& sessions,
                            const std::string& csv_path) {
  if (sessions.empty()) return loadLikertAnswers(csv_path);
  std::vector<std::string> items;
  for (const QuestionnaireItem& item : loadStudyProtocol(reportProtocolPath(args, sessions)).items)
    items.push_back(item.id);
  LikertAnswers answers = likertAnswersFromSessions(sessions, items);
  if (csv_path.empty()) return answers;
  const LikertAnswers csv = loadLikertAnswers(csv_path);
  for (size_t p = 0; p < csv.participants.size(); ++p) {
    const auto row =
        std::find(answers.participants.begin(), answers.participants.end(), csv.participants[p]);
    for (size_t i = 0; i < csv.items.size(); ++i) {
      const int j = answers.itemIndex(csv.items[i]);
      const std::optional<int> journal =
          row == answers.participants.end() || j < 0
              ? std::nullopt
              : answers.answers[size_t(row - answers.participants.begin())][size_t(j)];
      if (row != answers.participants.end() && csv.answers[p][i] == journal) continue;
      std::fprintf(stderr,
                   "cloudbrush study: report: %s: %s %s differs from the journals (which the "
                   "report uses)\n",
                   csv_path.c_str(), csv.participants[p].c_str(), csv.items[i].c_str());
    }
  }
  return answers;
}

int runReport(Args& args) {
  auto unknown = args.unknown({"help", "out", "constructs", "pair", "title", "protocol"});
  if (!unknown.empty()) return fail("report: unknown option " + unknown[0] + " (see --help)", 2);
  // The answers: from the journals when sessions are given (ANSWERS.csv, an export, is then
  // only compared with them), else from ANSWERS.csv.
  std::string csv_path;
  std::vector<std::string> journals;
  for (size_t i = 2; i < args.positional().size(); ++i) {
    const std::string& p = args.positional()[i];
    if (i == 2 && std::filesystem::path(p).extension() == ".csv")
      csv_path = p;
    else
      journals.push_back(p);
  }
  if (csv_path.empty() && journals.empty())
    return fail(
        "report: expected the answers: study report [ANSWERS.csv] [SESSION.cbj...] --out "
        "REPORT.html",
        2);
  const std::string out = args.get("out", "");
  if (out.empty()) return fail("report: --out REPORT.html is required", 2);
  StudyReportOptions options;
  options.answers_name = csv_path.empty() ? "the sessions' journals" : csv_path;
  options.title = args.get("title", options.title);
  if (auto pair = args.get("pair")) {
    const size_t comma = pair->find(',');
    if (comma == std::string::npos || comma == 0 || comma + 1 == pair->size())
      return fail("report: --pair '" + *pair + "': expected FIRST,SECOND item ids, e.g. Q3,Q6", 2);
    options.paired_first = pair->substr(0, comma);
    options.paired_second = pair->substr(comma + 1);
  }
  try {
    std::vector<SessionTrace> sessions;
    for (const std::string& journal : journals) sessions.push_back(loadSessionTrace(journal));
    const LikertAnswers answers = reportAnswers(args, sessions, csv_path);
    chooseReportConstructs(args, sessions, &options);
    const StudyReport report = computeStudyReport(answers, options, sessions);
    std::string error;
    if (!writeStudyFile(
            out,
            [&](std::ostream& s) {
              s << studyReportHtml(report, options, answers.scale_min, answers.scale_max);
            },
            &error))
      return fail(error);
    for (const ConstructSummary& c : report.constructs)
      for (const std::string& id : c.missing_items)
        std::fprintf(stderr, "cloudbrush study: report: construct '%s': no item %s in %s\n",
                     c.definition.name.c_str(), id.c_str(), options.answers_name.c_str());
    if (!report.paired_problem.empty())
      std::fprintf(stderr, "cloudbrush study: %s\n", report.paired_problem.c_str());
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return 0;
}

// `study check|run [PROTOCOL.toml]`: the protocol named (default the bundled one), read whole.
// 0, or the exit status after the error was printed.
int loadProtocolArgument(Args& args, const std::string& verb, std::string* path,
                         StudyProtocol* protocol) {
  if (args.positional().size() > 3)
    return fail(verb + ": expected at most one protocol: study " + verb + " [PROTOCOL.toml]", 2);
  *path = args.positional().size() == 3 ? args.positional()[2] : defaultStudyProtocolPath();
  try {
    *protocol = loadStudyProtocol(*path);
  } catch (const StudyProtocolError& e) {
    return fail(verb + ": " + e.what());
  }
  return 0;
}

int runCheck(Args& args) {
  auto unknown = args.unknown({"help", "vocabulary"});
  if (!unknown.empty()) return fail("check: unknown option " + unknown[0] + " (see --help)", 2);
  if (args.has("vocabulary")) {
    std::fputs(tutorialVocabularyText().c_str(), stdout);
    return 0;
  }
  std::string path;
  StudyProtocol protocol;
  if (const int code = loadProtocolArgument(args, "check", &path, &protocol)) return code;
  std::fputs(studyProtocolSummary(protocol).c_str(), stdout);
  const std::vector<std::string> missing = missingProtocolFiles(protocol);
  for (const std::string& file : missing)
    std::fprintf(stderr, "cloudbrush study: %s: missing file %s\n", path.c_str(), file.c_str());
  return missing.empty() ? 0 : 3;
}

int runWithdraw(Args& args) {
  auto unknown = args.unknown({"help", "data", "participant", "key-file", "dry-run"});
  if (!unknown.empty()) return fail("withdraw: unknown option " + unknown[0] + " (see --help)", 2);
  if (args.positional().size() != 2)
    return fail("withdraw: no positional arguments: --data DIR --participant ID", 2);
  const std::string data = args.get("data", ""), participant = args.get("participant", "");
  if (data.empty() || participant.empty())
    return fail("withdraw: --data DIR and --participant ID are required", 2);
  const bool dry_run = args.has("dry-run");
  WithdrawalResult result;
  try {
    result = withdrawParticipant(data, participant, args.get("key-file", ""), dry_run);
  } catch (const std::exception& e) {
    return fail("withdraw: " + std::string(e.what()));
  }
  const char* verb = dry_run ? "would delete" : "deleted";
  for (const auto& path : result.removed_paths) std::printf("%s %s\n", verb, path.string().c_str());
  for (const CsvRowRemoval& removal : result.removed_rows)
    std::printf("%s %d row%s of %s from %s\n", verb, removal.rows, removal.rows == 1 ? "" : "s",
                participant.c_str(), removal.file.string().c_str());
  for (const auto& path : result.still_mentioning)
    std::fprintf(stderr,
                 "cloudbrush study: withdraw: %s still mentions %s (not a CSV with a "
                 "participant or session column; edit it by hand)\n",
                 path.string().c_str(), participant.c_str());
  return result.still_mentioning.empty() ? 0 : 3;
}

std::atomic<bool> g_study_stop{false};
void onStudySignal(int) {
  g_study_stop.store(true);
}

int64_t monotonicNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// What a session folder's journal holds for `study run --resume`.
struct FolderJournal {
  JournalReadResult read;
  std::optional<StudySessionInfo> info;  // its study.info marker (none: nothing to resume)
  std::vector<StudyRunRecord> markers;   // its other study.* markers, in order
  std::vector<size_t> marker_record;     // each marker's index in read.records
  int64_t last_record_ns = 0, last_sample_ns = -1;
};

FolderJournal readFolderJournal(const std::string& path) {
  FolderJournal f;
  f.read = readJournal(path);
  for (size_t i = 0; i < f.read.records.size(); ++i) {
    const JournalRecord& r = f.read.records[i];
    f.last_record_ns = i == 0 ? r.t_ns : std::max(f.last_record_ns, r.t_ns);
    if (r.type == JournalRecordType::kPenSample) f.last_sample_ns = r.t_ns;
    if (r.type != JournalRecordType::kMarker) continue;
    const std::string text(r.payload.begin(), r.payload.end());
    StudySessionInfo info;
    if (!f.info && parseStudyInfoMarker(text, &info)) {
      f.info = info;
    } else if (text.rfind("study.", 0) == 0) {
      f.markers.push_back({r.t_ns, text});
      f.marker_record.push_back(i);
    }
  }
  return f;
}

// A new session's participant and folder: --participant N, refused when the runner is to name
// the folder and N already has a session folder in the data directory (a second folder of one
// participant would hold a second first session; the one there is carried on with --resume),
// else the next free number; then the clock anchor and the folder, made (--resume FOLDER with no
// session in it yet starts one in FOLDER, the operator's choice). 0, or the exit status after the
// error was printed.
int newSessionFolder(Args& args, const StudyProtocol& protocol, const std::string& resume_folder,
                     int participant, StudySessionInfo* info, std::string* folder) {
  std::error_code ec;
  const std::string data_dir = resume_folder.empty()
                                   ? args.get("data-dir", stateDir() + "/study")
                                   : std::filesystem::path(resume_folder).parent_path().string();
  std::filesystem::create_directories(data_dir.empty() ? "." : data_dir, ec);
  if (ec) return fail("run: --data-dir " + data_dir + ": " + ec.message());
  const auto id_for = [&](int n) { return protocol.participant_ids.idFor(n); };
  if (participant > 0 && resume_folder.empty()) {  // (--resume FOLDER names the folder itself)
    const std::vector<std::string> existing =
        participantSessionFolders(data_dir.empty() ? "." : data_dir, id_for(participant));
    if (!existing.empty())
      return fail("run: --participant " + std::to_string(participant) + ": " + id_for(participant) +
                      " has a session folder already: " + existing.back() +
                      ". To carry that session on: cloudbrush study run --resume " +
                      existing.back() + " (same --size and --grid). To record a new participant, " +
                      "leave --participant out (the next free number is " +
                      std::to_string(nextFreeParticipantNumber(data_dir, id_for)) + ")",
                  2);
  }
  info->participant_number =
      participant > 0 ? participant : nextFreeParticipantNumber(data_dir, id_for);
  info->participant_id = id_for(info->participant_number);
  info->anchor_monotonic_ns = monotonicNowNs();
  info->anchor_unix_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::system_clock::now().time_since_epoch())
                             .count();
  *folder =
      resume_folder.empty()
          ? data_dir + "/" + studySessionFolderName(info->participant_id, info->anchor_unix_ns)
          : resume_folder;
  if (resume_folder.empty() && std::filesystem::exists(*folder))
    return fail("run: " + *folder + " exists already (one session per folder)");
  std::filesystem::create_directories(*folder, ec);
  if (ec) return fail("run: " + *folder + ": " + ec.message());
  return 0;
}

// What `study run` opens, in the order it opens them (and so closes them in reverse).
struct StudyRun {
  std::string resume_folder;  // --resume FOLDER
  FolderJournal previous;     // what its journal holds
  bool resuming = false;      // it holds a session to carry on
  std::string path;           // the protocol file
  StudyProtocol protocol;
  StudySessionInfo info;
  long participant = 0, grid = 256, frames = 0;
  double seconds = 0.0, end_seconds = 8.0;
  FrameLoopOptions loop_options;
  DisplayOptions display_options;
  std::string backend;
  JournalReadResult pen_input;  // --backend replay: the recorded pen
  std::string folder;
  std::unique_ptr<Display> display;
  RenderConfig render_config;
  MappingConfig mapping;
  PaintSessionSettings settings;
  BrushConfig brush;
  std::unique_ptr<PaintSession> session;
  JournalWriter journal;
  std::string journal_path;
  ResumedSession resumed;
  std::optional<int64_t> origin;  // the session clock's start on a recorded time line
  SyncMarkerSender sync_sender;   // task and stroke boundaries for other recorders (--sync-udp)
};

// The resumed folder's journal and the protocol, checked completely before anything opens: no
// session starts on a guess. 0, or the exit status after the error was printed.
int loadRunProtocol(Args& args, StudyRun* run) {
  // --resume FOLDER: a session folder; when its journal holds a session, it is carried on.
  run->resume_folder = args.get("resume", "");
  const std::string resume_journal = run->resume_folder + "/session.cbj";
  FolderJournal& previous = run->previous;
  std::error_code ec;
  if (!run->resume_folder.empty() && std::filesystem::exists(resume_journal, ec)) {
    previous = readFolderJournal(resume_journal);
    if (!previous.info && (!previous.markers.empty() || previous.last_sample_ns >= 0))
      return fail("run: --resume: " + resume_journal +
                  " holds pen samples or markers but no study.info record (not a study "
                  "session?); not resuming, and not overwriting it");
  }
  run->resuming = previous.info.has_value();
  // A resumed session reads the protocol it was started with, unless one is named.
  if (run->resuming && args.positional().size() < 3) {
    run->path = previous.info->protocol_file;
    try {
      run->protocol = loadStudyProtocol(run->path);
    } catch (const StudyProtocolError& e) {
      return fail(std::string("run: --resume: ") + e.what());
    }
  } else if (const int code = loadProtocolArgument(args, "run", &run->path, &run->protocol)) {
    return code;
  }
  const std::vector<std::string> missing = missingProtocolFiles(run->protocol);
  for (const std::string& file : missing)
    std::fprintf(stderr, "cloudbrush study: run: %s: missing file %s\n", run->path.c_str(),
                 file.c_str());
  if (!missing.empty()) return 3;
  return 0;
}

// The session's protocol, operator and venue into run->info (a resumed session's own record
// says who and where), checked against the protocol. 0, or the exit status.
int readRunInfo(Args& args, StudyRun* run) {
  const StudyProtocol& protocol = run->protocol;
  StudySessionInfo& info = run->info;
  info.protocol_name = protocol.name;
  info.protocol_version = protocol.version;
  info.protocol_file = std::filesystem::absolute(run->path).string();
  info.operator_initials = args.get("operator", "");
  info.venue = args.get("venue", protocol.venues.size() == 1 ? protocol.venues[0].id : "");
  if (run->resuming) {  // who, where and when come from the session's own record
    info.operator_initials = run->previous.info->operator_initials;
    info.venue = run->previous.info->venue;
  }
  if (protocol.operator_required && info.operator_initials.empty())
    return fail("run: " + run->path + ": the protocol requires the operator: --operator INITIALS",
                2);
  if (!protocol.venues.empty()) {
    std::string ids;
    bool known = false;
    for (const StudyVenue& v : protocol.venues) {
      ids += (ids.empty() ? "" : ", ") + v.id;
      known = known || v.id == info.venue;
    }
    if (!known)
      return fail("run: --venue: expected one of the protocol's venues (" + ids + "), got '" +
                      info.venue + "'",
                  2);
  }
  return 0;
}

// The run's options (participant, grid, frames, keys, display, size, pen backend) and with
// --backend replay the recorded pen, read now so the session's clock can follow its time line.
// 0, or the exit status.
int readRunOptions(Args& args, StudyRun* run) {
  run->participant = args.getInt("participant", 0);
  run->grid = args.getInt("grid", 256);
  run->frames = args.getInt("frames", 0);
  run->seconds = args.getDouble("seconds", 0.0);
  run->end_seconds = args.getDouble("end-seconds", 8.0);
  if (!args.error().empty()) return fail("run: " + args.error(), 2);
  if (args.has("participant") && run->participant < 1)
    return fail("run: --participant " + args.get("participant", "") +
                    ": expected N >= 1 (participant numbers start at 1: " +
                    run->protocol.participant_ids.idFor(1) +
                    " is 1); leave --participant out to take the next free number",
                2);
  if (run->grid < 8 || run->grid > 1024) return fail("run: --grid: expected 8..1024", 2);
  std::string error;
  if (args.has("keys") &&
      !parseKeyList(args.get("keys", ""), &run->loop_options.initial_keys, &error))
    return fail("run: --keys: " + error, 2);
  DisplayOptions& display_options = run->display_options;
  const std::string platform = args.get("display", "auto");
  if (!parseDisplayPlatform(platform, &display_options.platform))
    return fail("run: --display: expected auto, kms, x11 or surfaceless, got '" + platform + "'",
                2);
  display_options.drm_device = args.get("drm-device", "");
  const std::string size = args.get("size", "1280x720");
  int consumed = 0;
  if (std::sscanf(size.c_str(), "%dx%d%n", &display_options.width, &display_options.height,
                  &consumed) != 2 ||
      consumed != int(size.size()) || display_options.width < 320 || display_options.height < 240 ||
      display_options.width > 16384 || display_options.height > 16384)
    return fail("run: --size: expected WxH (320x240 .. 16384x16384), got '" + size + "'", 2);
  run->backend = args.get("backend", "auto");
  if (run->backend == "replay" && !args.has("journal"))
    return fail("run: --backend replay needs --journal FILE", 2);
  if (run->backend == "replay") {
    run->pen_input = readJournal(args.get("journal", ""));
    if (run->pen_input.version == 0) return fail("run: --journal: " + run->pen_input.error, 2);
  }
  return 0;
}

// The session folder, before the display: a folder that cannot be written stops here. A resumed
// session keeps its participant and clock anchor. 0, or the exit status.
int openRunFolder(Args& args, StudyRun* run) {
  StudySessionInfo& info = run->info;
  const FolderJournal& previous = run->previous;
  if (run->resuming) {
    run->folder = run->resume_folder;
    info.participant_number = previous.info->participant_number;
    info.participant_id = run->protocol.participant_ids.idFor(info.participant_number);
    info.anchor_monotonic_ns = previous.info->anchor_monotonic_ns;
    info.anchor_unix_ns = previous.info->anchor_unix_ns;
    // The pen an earlier run recorded stays in session.json until this run's pen connects.
    std::ifstream earlier(run->folder + "/session.json", std::ios::binary);
    const std::string earlier_json((std::istreambuf_iterator<char>(earlier)),
                                   std::istreambuf_iterator<char>());
    info.earlier_device_json = deviceJsonIn(earlier_json);
  } else if (const int code = newSessionFolder(args, run->protocol, run->resume_folder,
                                               int(run->participant), &info, &run->folder)) {
    return code;
  }
  const int number = info.participant_number;
  for (const StudyTask* task : run->protocol.tasksForParticipant(number))
    info.task_order.push_back(task->id);
  std::printf("session folder: %s\nparticipant: %s (number %d)\n", run->folder.c_str(),
              info.participant_id.c_str(), number);
  std::fflush(stdout);
  return 0;
}

// The display, render.toml and mapping.toml, and the painting session (replayed from the
// folder's journal when resuming). 0, or the exit status.
int openRunSession(StudyRun* run) {
  std::string error;
  StudySessionInfo& info = run->info;
  std::string choice_note;
  run->display = openDisplay(run->display_options, &error, &choice_note);
  if (!run->display) return fail("run: " + error);
  info.display_platform = run->display->platformName();
  info.display_width = run->display->width();
  info.display_height = run->display->height();
  info.refresh_hz = run->display->refreshHz(&info.refresh_note);
  try {
    if (std::filesystem::exists(configFile("render.toml")))
      run->render_config = loadRenderConfig(configFile("render.toml"));
    if (std::filesystem::exists(configFile("mapping.toml")))
      run->mapping = loadMappingConfig(configFile("mapping.toml"));
  } catch (const std::exception& e) {
    return fail(std::string("run: ") + e.what());
  }
  PaintSessionSettings& settings = run->settings;
  settings.screen_width = run->display->width();
  settings.screen_height = run->display->height();
  settings.grid = int(run->grid);
  run->brush = loadDefaultBrushConfig();
  settings.auto_end_still_ms = run->brush.stroke.auto_end_still_ms;
  settings.auto_end_light_ms = run->brush.stroke.auto_end_light_ms;
  run->journal_path = run->folder + "/session.cbj";
  if (run->resuming) {
    // The journal replayed into the session (the settings recorded in it), appended to after
    // its last whole record.
    if (!resumeOrStartSession(run->journal_path, settings, run->brush, run->mapping, &run->journal,
                              &run->resumed, &error))
      return fail("run: --resume: " + error, 2);
    if (!run->resumed.warning.empty())
      std::fprintf(stderr, "cloudbrush study: resume: %s\n", run->resumed.warning.c_str());
    run->session = std::move(run->resumed.session);
  } else {
    run->session = std::make_unique<PaintSession>(settings, run->brush, run->mapping);
  }
  return 0;
}

// The session clock's origin, a new session's journal (render settings, study.info) and the
// sync sender. 0, or the exit status.
int startRunJournal(Args& args, StudyRun* run) {
  std::string error;
  StudySessionInfo& info = run->info;
  const FolderJournal& previous = run->previous;
  // The session's clock: the monotonic clock, or with a recorded pen the recording's own time
  // line (a TimelineClock from `origin`), so that frames, the runner's timers and its records
  // keep to the pen's time and a resumed run carries on from the last record's time. (Made
  // just before the loop, so starting up does not run the clock on.)
  std::optional<int64_t>& origin = run->origin;
  if (run->backend == "replay") {
    origin = previous.last_record_ns;
    if (!run->resuming)
      for (const JournalRecord& r : run->pen_input.records)
        if (r.type == JournalRecordType::kPenSample) {
          origin = r.t_ns;
          break;
        }
    if (!run->resuming) info.anchor_monotonic_ns = *origin;
  } else if (run->resuming && monotonicNowNs() < previous.last_record_ns) {
    // The machine restarted since (its monotonic clock began again): carry on from the record.
    origin = previous.last_record_ns;
  }
  PaintSession& session = *run->session;
  JournalWriter& journal = run->journal;
  if (!run->resuming) {
    // The render settings in force, journalled with the brush and mapping
    // (drivers/core/JOURNAL.md).
    session.setRenderSettings(formatRenderConfig(run->render_config), info.anchor_monotonic_ns);
    session.setStartingLight(run->render_config.light);
    session.setStartingStyle(renderStyleName(run->render_config.options.style));
    if (!journal.open(run->journal_path)) return fail("run: " + journal.error());
    session.recordTo(&journal, info.anchor_monotonic_ns);
    if (!journal.append(JournalRecordType::kMarker, info.anchor_monotonic_ns,
                        formatStudyInfoMarker(info)))
      return fail("run: " + journal.error());
  }
  if (args.has("sync-udp")) {
    if (!run->sync_sender.open(args.get("sync-udp", ""), &error))
      return fail("run: --sync-udp: " + error, 2);
    session.setSyncSender(&run->sync_sender);
  }
  return 0;
}

// The pen: the recorded one on the session's clock (a resumed session's carries on after the
// last sample its journal holds), a device, or none (--backend none). nullptr with *status set
// when the device does not open.
std::unique_ptr<PenSource> openRunPen(Args& args, StudyRun* run, Clock* clock, int* status) {
  std::string error;
  std::unique_ptr<PenSource> pen;
  if (run->backend == "replay") {
    std::vector<JournalRecord> rest;
    for (JournalRecord& r : run->pen_input.records)
      if (r.type != JournalRecordType::kPenSample || r.t_ns > run->previous.last_sample_ns)
        rest.push_back(std::move(r));
    ReplayOptions replay;
    replay.timeline = true;
    pen = std::make_unique<ReplayPenSource>(std::move(rest), replay, clock);
  } else if (run->backend != "none") {
    PenSourceOptions pen_options;
    pen_options.backend = run->backend;
    pen_options.device = args.get("pen-device", "");
    pen = openPenSource(pen_options, &error);
    if (!pen) *status = fail("run: --backend " + run->backend + ": " + error, 2);
  }
  return pen;
}

// A resumed session: the runner's state restored from the study records, the stage's setup done
// again when nothing was painted since it began (the journal may have lost the setup itself).
// 0, or the exit status.
int restoreRunState(const StudyRun& run, int64_t start_ns, StudyRunState* state,
                    StudyRunOptions* options) {
  std::string error;
  const FolderJournal& previous = run.previous;
  if (!state->restore(previous.markers, &error))
    return fail("run: --resume: " + run.journal_path + ": " + error);
  state->resumedAfter(previous.last_record_ns, start_ns);
  const int begin = state->restoredStageBegin();
  bool painted_since = false;
  if (begin >= 0)
    for (size_t i = previous.marker_record[size_t(begin)] + 1; i < previous.read.records.size();
         ++i)
      painted_since =
          painted_since || previous.read.records[i].type == JournalRecordType::kPenSample;
  options->set_up_stage = !painted_since;
  options->resumed = true;
  options->last_mapped = run.resumed.replay.last_mapped;
  std::printf("resumed %s: %zu records, %zu pen samples, %u strokes, %zu study records; stage %s\n",
              run.folder.c_str(), run.resumed.replay.records_applied,
              run.resumed.replay.pen_samples, run.resumed.replay.strokes_mapped,
              previous.markers.size(), studyStageName(state->stage()));
  std::fflush(stdout);
  return 0;
}

// The session on the display: renderer, clock, pen and the runner's screen in the frame loop
// until the session ends, a signal, --frames or --seconds; the exit status.
int runStudyLoop(Args& args, StudyRun& run) {
  std::string error;
  const StudySessionInfo& info = run.info;
  PaintSession& session = *run.session;
  JournalWriter& journal = run.journal;
  VolumeRenderer renderer;
  if (!renderer.init(&error)) return fail("run: " + error);
  std::unique_ptr<Clock> clock;
  if (run.origin)
    clock = std::make_unique<TimelineClock>(*run.origin);
  else
    clock = std::make_unique<MonotonicClock>();
  // Sync markers' wall times at their events, on the session's clock.
  session.setSyncClock([clock = clock.get()] { return clock->nowNs(); });
  const int64_t start_ns = run.resuming ? clock->nowNs() : info.anchor_monotonic_ns;
  int pen_status = 0;
  std::unique_ptr<PenSource> pen = openRunPen(args, &run, clock.get(), &pen_status);
  if (pen_status) return pen_status;

  const FolderJournal& previous = run.previous;
  StudyRunState state(
      run.protocol, info.participant_number,
      previous.markers.empty() ? info.anchor_monotonic_ns : previous.markers.front().t_ns);
  StudyRunOptions options;
  if (run.resuming)
    if (const int code = restoreRunState(run, start_ns, &state, &options)) return code;
  options.folder = run.folder;
  options.info = info;
  options.start_ns = start_ns;
  options.end_seconds = run.end_seconds;
  options.paint.render = run.render_config.options;
  options.paint.moving_scale = run.render_config.moving_scale;
  options.paint.config_dir = defaultConfigDir();
  options.paint.state_dir = stateDir();
  options.paint.clock = clock.get();
  StudyRunScreen screen(*run.display, renderer, session, pen.get(), &journal, state, options);
  std::signal(SIGINT, onStudySignal);
  std::signal(SIGTERM, onStudySignal);
  FrameLoopOptions& loop_options = run.loop_options;
  loop_options.stop = &g_study_stop;
  loop_options.clock = clock.get();
  // Durability: the session syncs the journal at every stroke end; the loop at least once a second.
  const MonotonicClock sync_clock;
  loop_options.each_iteration = [&journal, &sync_clock](bool) {
    if (journal.isOpen() && !journal.syncIfDue(sync_clock.nowNs()))
      std::fprintf(stderr, "cloudbrush study: journal: %s\n", journal.error().c_str());
  };
  loop_options.max_frames = run.frames;
  loop_options.max_seconds = run.seconds;
  FrameLoop loop(*run.display, pen.get());
  FrameLoopResult result;
  const bool ran = loop.run(screen, loop_options, &result, &error);
  journal.sync();
  if (!ran) return fail("run: " + error);
  std::printf("cloudbrush study: %s after %ld frames (%.1f s): stage %s%s\n",
              result.quit_reason.c_str(), result.frames, result.seconds,
              studyStageName(state.stage()),
              state.aborted() ? (", aborted: " + state.abortReason()).c_str() : "");
  std::printf("cloudbrush study: volume checksum %016llx\n",
              static_cast<unsigned long long>(volumeChecksum(session.volume())));
  if (state.declined())
    std::printf(
        "cloudbrush study: %s declined consent; the session ended before any task. %s "
        "holds session.json (status \"declined\") and the journal, no task data.\n",
        state.participantId().c_str(), run.folder.c_str());
  for (const std::string& problem : screen.problems())
    std::fprintf(stderr, "cloudbrush study: problem: %s\n", problem.c_str());
  return screen.problems().empty() ? 0 : 1;
}

int runStudySession(Args& args) {
  auto unknown = args.unknown({"help", "data-dir", "participant", "venue", "operator", "display",
                               "drm-device", "size", "grid", "backend", "pen-device", "journal",
                               "keys", "frames", "seconds", "end-seconds", "sync-udp", "resume"});
  if (!unknown.empty()) return fail("run: unknown option " + unknown[0] + " (see --help)", 2);
  StudyRun run;
  if (const int code = loadRunProtocol(args, &run)) return code;
  if (const int code = readRunInfo(args, &run)) return code;
  if (const int code = readRunOptions(args, &run)) return code;
  if (const int code = openRunFolder(args, &run)) return code;
  if (const int code = openRunSession(&run)) return code;
  if (const int code = startRunJournal(args, &run)) return code;
  return runStudyLoop(args, run);
}

}  // namespace

int commandStudy(int argc, char** argv) {
  Args args(argc, argv, {"help", "volumes", "render", "vocabulary", "dry-run", "merge"});
  if (args.has("help") || args.positional().size() < 2) {
    std::fputs(kStudyHelp, args.has("help") ? stdout : stderr);
    return args.has("help") ? 0 : 2;
  }
  if (!args.error().empty()) return fail(args.error(), 2);
  const std::string& action = args.positional()[1];
  if (action == "export") return runExport(args);
  if (action == "volume") return runVolume(args);
  if (action == "report") return runReport(args);
  if (action == "check") return runCheck(args);
  if (action == "withdraw") return runWithdraw(args);
  if (action == "run") return runStudySession(args);
  return fail("unknown action '" + action +
                  "' (export, volume, report, check, withdraw or run; see --help)",
              2);
}

}  // namespace cb
