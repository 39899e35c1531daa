// A study session's folder ("The record"): one folder per session under the data
// directory, named `<participant id>-<UTC start, YYYYmmddTHHMMSSZ>` (so `study withdraw` finds
// it by the id), holding
//   session.json        what the session ran on (below), rewritten when the session ends
//   session.cbj         the journal (drivers/core/JOURNAL.md), study stages as Marker records
//   questionnaire.csv   participant,Q1..Qn (likert_answers.h), NA for missing
//   demographics.csv    participant, demographic fields, free-text answers, NA for missing
//   tasks/<task id>.*   what each task's `save` asks for (volume_export.h, render_export.h)
//
// session.json fields: format (1), status ("running" | "completed" | "aborted" | "declined": the
// participant did not consent, so no stage after consent ran), abort_reason,
// protocol {name, version, file}, participant {id, number}, venue, operator, software {name,
// version}, device {name, usb_vendor, usb_product, serial (what the device reports, PenSource::
// serialNumber; null when it reports none, with serial_note saying why), x_max, y_max,
// x_res_per_mm, y_res_per_mm, pressure_max, tilt_min, tilt_max, distance_max} or null before a
// pen connected, calibration (the profile in force, TOML text), display {platform, width,
// height, refresh_hz (the mode's rate, Display::refreshHz; null when there is none, with
// refresh_note saying why)}, clock_anchor {monotonic_ns,
// wall_clock_utc, wall_clock_unix_ns} (the same instant on both clocks: journal times are
// monotonic), task_order [ids], storage (study_storage_watch.h: ok, failing or recovered, and
// each outage of writing to the folder; a resumed run reports its own), stages_completed
// [names].
#pragma once

#include "app/core/atomic_file.h"  // writeFileAtomically, for the session files

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "drivers/core/pen_sample.h"

namespace cb {

struct StudySessionInfo {
  std::string status = "running";
  std::string abort_reason;
  std::string protocol_name, protocol_version, protocol_file;
  std::string participant_id;
  int participant_number = 0;
  std::string venue, operator_initials;
  std::optional<PenDeviceInfo> device;
  std::string device_serial, device_serial_note;  // "" serial: none, the note says why
  // Without `device`: the device object an earlier run of this session wrote (deviceJsonIn of
  // its session.json), kept so that a resumed run whose pen never connects (the session was
  // already complete, say) does not overwrite it with null; "" writes null.
  std::string earlier_device_json;
  std::string calibration_toml;
  std::string display_platform;
  int display_width = 0, display_height = 0;
  std::optional<double> refresh_hz;
  std::string refresh_note;  // why refresh_hz is null
  int64_t anchor_monotonic_ns = 0, anchor_unix_ns = 0;
  std::vector<std::string> task_order, stages_completed;
  std::string storage_json;  // StudyStorageWatch::json(); "" writes {"status": "ok", ...}
};

// This build's version (CMake's project version).
const char* cloudbrushVersion();

// The session's fixed facts as a journal marker, written first, so a restarted runner finds them
// in the journal alone: `study.info protocol_file=PATH protocol=NAME version=V participant=ID
// number=N venue=V operator=O monotonic_ns=T wall_clock_unix_ns=T` (study_marker_text.h).
std::string formatStudyInfoMarker(const StudySessionInfo& info);
// Fills those fields of *info from such a marker; false when `text` is not one.
bool parseStudyInfoMarker(const std::string& text, StudySessionInfo* info);

// `<id>-<UTC time of unix_ns>`.
std::string studySessionFolderName(const std::string& participant_id, int64_t unix_ns);

// session.json's text.
std::string formatStudySessionJson(const StudySessionInfo& info);
// The "device" object of a session.json this build wrote (formatStudySessionJson writes it on
// one line), as JSON text; "" when it is null or not there.
std::string deviceJsonIn(const std::string& session_json);

// The session folders of participant `id` in `data_dir` (`<id>-...`), as paths, sorted; empty
// when it has none (or `data_dir` does not exist).
std::vector<std::string> participantSessionFolders(const std::string& data_dir,
                                                   const std::string& id);

// The lowest participant number >= 1 whose id names no folder in `data_dir` yet (folders are
// `<id>-...`).
int nextFreeParticipantNumber(const std::string& data_dir,
                              const std::function<std::string(int)>& id_for);

}  // namespace cb
