// The text of the journal's newer record types (JOURNAL.md §8–10), formatted and parsed in one
// place so the painter, replay and the study exports agree:
//   Settings (8)     "# NAME\n" + that config file's TOML (brush.toml, mapping.toml, render.toml)
//   StrokeMapped (9) "stroke = N\nmapping_ms = X\n" — a measurement, never an input
//   Sync (10)        one line, also the UDP datagram: "cloudbrush-sync v1 seq=S kind=K
//                    mono_ns=T wall_ns=W label=TEXT" (label last; it may hold spaces)
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace cb {

std::string formatSettingsRecord(const std::string& config_name, const std::string& toml);
// False with *error when the first line is not "# NAME".
bool parseSettingsRecord(std::string_view text, std::string* config_name, std::string* toml,
                         std::string* error);

std::string formatStrokeMapped(uint32_t stroke_index, double mapping_ms);
struct StrokeMappedRecord {
  uint32_t stroke = 0;
  double mapping_ms = 0.0;
};
std::optional<StrokeMappedRecord> parseStrokeMapped(std::string_view text);

// Kinds the painter sends: task_begin, task_end (the study runner's tasks), stroke_begin,
// stroke_end (label: the stroke's index); any other word is allowed.
struct SyncMarker {
  uint64_t seq = 0;     // 1, 2, ... per session (a receiver sees what it missed)
  std::string kind;     // one word
  int64_t mono_ns = 0;  // CLOCK_MONOTONIC, the journal's clock
  int64_t wall_ns = 0;  // CLOCK_REALTIME (ns since 1970), for recorders on other clocks
  std::string label;    // free text on one line
};
std::string formatSyncMarker(const SyncMarker& marker);
std::optional<SyncMarker> parseSyncMarker(std::string_view text);

}  // namespace cb
