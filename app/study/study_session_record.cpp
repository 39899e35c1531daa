#include "app/study/study_session_record.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "app/core/json_text.h"
#include "app/study/csv_text.h"
#include "app/study/study_marker_text.h"

#ifndef CB_VERSION
#define CB_VERSION "unknown"
#endif

namespace cb {
namespace {

std::string jsonList(const std::vector<std::string>& values) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + jsonString(values[i]);
  return out + "]";
}

std::string utcText(int64_t unix_ns, const char* format) {
  const std::time_t seconds = std::time_t(unix_ns / 1'000'000'000);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char text[64];
  std::strftime(text, sizeof text, format, &tm);
  return text;
}

}  // namespace

const char* cloudbrushVersion() {
  return CB_VERSION;
}

std::string formatStudyInfoMarker(const StudySessionInfo& info) {
  return "study.info protocol_file=" + studyMarkerValue(info.protocol_file) +
         " protocol=" + studyMarkerValue(info.protocol_name) +
         " version=" + studyMarkerValue(info.protocol_version) +
         " participant=" + studyMarkerValue(info.participant_id) +
         " number=" + std::to_string(info.participant_number) +
         " venue=" + studyMarkerValue(info.venue) +
         " operator=" + studyMarkerValue(info.operator_initials) +
         " monotonic_ns=" + std::to_string(info.anchor_monotonic_ns) +
         " wall_clock_unix_ns=" + std::to_string(info.anchor_unix_ns);
}

bool parseStudyInfoMarker(const std::string& text, StudySessionInfo* info) {
  const StudyMarkerFields m = parseStudyMarker(text);
  if (m.event != "study.info" || !m.has("protocol_file") || !m.has("number")) return false;
  info->protocol_file = m.get("protocol_file");
  info->protocol_name = m.get("protocol");
  info->protocol_version = m.get("version");
  info->participant_id = m.get("participant");
  info->participant_number = std::atoi(m.get("number").c_str());
  info->venue = m.get("venue");
  info->operator_initials = m.get("operator");
  info->anchor_monotonic_ns = std::atoll(m.get("monotonic_ns").c_str());
  info->anchor_unix_ns = std::atoll(m.get("wall_clock_unix_ns").c_str());
  return true;
}

std::string studySessionFolderName(const std::string& participant_id, int64_t unix_ns) {
  return participant_id + "-" + utcText(unix_ns, "%Y%m%dT%H%M%SZ");
}

std::string formatStudySessionJson(const StudySessionInfo& info) {
  std::string j = "{\n";
  j += "  \"format\": 1,\n";
  j += "  \"status\": " + jsonString(info.status) + ",\n";
  j += "  \"abort_reason\": " +
       (info.abort_reason.empty() ? std::string("null") : jsonString(info.abort_reason)) + ",\n";
  j += "  \"protocol\": {\"name\": " + jsonString(info.protocol_name) +
       ", \"version\": " + jsonString(info.protocol_version) +
       ", \"file\": " + jsonString(info.protocol_file) + "},\n";
  j += "  \"participant\": {\"id\": " + jsonString(info.participant_id) +
       ", \"number\": " + std::to_string(info.participant_number) + "},\n";
  j += "  \"venue\": " + jsonString(info.venue) + ",\n";
  j += "  \"operator\": " + jsonString(info.operator_initials) + ",\n";
  j +=
      "  \"software\": {\"name\": \"cloudbrush\", \"version\": " + jsonString(cloudbrushVersion()) +
      "},\n";
  if (info.device) {
    const PenDeviceInfo& d = *info.device;
    const std::string& d_serial = info.device_serial;
    char ids[32];
    std::snprintf(ids, sizeof ids, "\"%04x\", \"usb_product\": \"%04x\"", d.usb_vendor,
                  d.usb_product);
    j += "  \"device\": {\"name\": " + jsonString(d.name) + ", \"usb_vendor\": " + ids +
         ", \"serial\": " +
         (d_serial.empty() ? "null, \"serial_note\": " + jsonString(info.device_serial_note)
                           : jsonString(d_serial)) +
         ", \"x_max\": " + std::to_string(d.x_max) + ", \"y_max\": " + std::to_string(d.y_max) +
         ", \"x_res_per_mm\": " + csvDouble(d.x_res) + ", \"y_res_per_mm\": " + csvDouble(d.y_res) +
         ", \"pressure_max\": " + std::to_string(d.pressure_max) +
         ", \"tilt_min\": " + std::to_string(d.tilt_min) +
         ", \"tilt_max\": " + std::to_string(d.tilt_max) +
         ", \"distance_max\": " + std::to_string(d.distance_max) + "},\n";
  } else if (!info.earlier_device_json.empty()) {
    j += "  \"device\": " + info.earlier_device_json + ",\n";
  } else {
    j += "  \"device\": null,\n";
  }
  j += "  \"calibration\": " + jsonString(info.calibration_toml) + ",\n";
  j += "  \"display\": {\"platform\": " + jsonString(info.display_platform) +
       ", \"width\": " + std::to_string(info.display_width) +
       ", \"height\": " + std::to_string(info.display_height) + ", \"refresh_hz\": " +
       (info.refresh_hz ? csvDouble(*info.refresh_hz)
                        : "null, \"refresh_note\": " + jsonString(info.refresh_note)) +
       "},\n";
  j += "  \"clock_anchor\": {\"monotonic_ns\": " + std::to_string(info.anchor_monotonic_ns) +
       ", \"wall_clock_utc\": " + jsonString(utcText(info.anchor_unix_ns, "%Y-%m-%dT%H:%M:%S")) +
       ", \"wall_clock_unix_ns\": " + std::to_string(info.anchor_unix_ns) + "},\n";
  j += "  \"task_order\": " + jsonList(info.task_order) + ",\n";
  j += "  \"storage\": " +
       (info.storage_json.empty() ? std::string("{\"status\": \"ok\", \"outages\": []}")
                                  : info.storage_json) +
       ",\n";
  j += "  \"stages_completed\": " + jsonList(info.stages_completed) + "\n";
  return j + "}\n";
}

std::string deviceJsonIn(const std::string& session_json) {
  const std::string key = "\n  \"device\": {";
  const size_t at = session_json.find(key);
  if (at == std::string::npos) return "";
  const size_t begin = at + key.size() - 1;  // the '{'
  const size_t end = session_json.find("},\n", begin);
  if (end == std::string::npos) return "";
  return session_json.substr(begin, end + 1 - begin);
}

std::vector<std::string> participantSessionFolders(const std::string& data_dir,
                                                   const std::string& id) {
  std::vector<std::string> folders;
  std::error_code ec;
  const std::string prefix = id + "-";
  for (const auto& entry : std::filesystem::directory_iterator(data_dir, ec))
    if (entry.path().filename().string().rfind(prefix, 0) == 0 && entry.is_directory(ec))
      folders.push_back(entry.path().string());
  std::sort(folders.begin(), folders.end());
  return folders;
}

int nextFreeParticipantNumber(const std::string& data_dir,
                              const std::function<std::string(int)>& id_for) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(data_dir, ec))
    names.push_back(entry.path().filename().string());
  for (int n = 1;; ++n) {
    const std::string prefix = id_for(n) + "-";
    bool used = false;
    for (const std::string& name : names) used = used || name.rfind(prefix, 0) == 0;
    if (!used) return n;
  }
}

}  // namespace cb
