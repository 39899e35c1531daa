#include "drivers/core/journal_records.h"

#include <cstdio>
#include <cstdlib>

namespace cb {
namespace {

// The value after "key=" in a space-separated line, up to the next space (or the end when
// `rest_of_line`).
std::optional<std::string> field(std::string_view line, std::string_view key, bool rest_of_line) {
  const std::string needle = " " + std::string(key) + "=";
  const size_t at = line.find(needle);
  if (at == std::string_view::npos) return std::nullopt;
  const size_t begin = at + needle.size();
  const size_t end = rest_of_line ? line.size() : line.find(' ', begin);
  return std::string(
      line.substr(begin, (end == std::string_view::npos ? line.size() : end) - begin));
}

bool parseInt64(const std::string& text, int64_t* out) {
  if (text.empty()) return false;
  char* end = nullptr;
  *out = std::strtoll(text.c_str(), &end, 10);
  return *end == '\0';
}

}  // namespace

std::string formatSettingsRecord(const std::string& config_name, const std::string& toml) {
  return "# " + config_name + "\n" + toml;
}

bool parseSettingsRecord(std::string_view text, std::string* config_name, std::string* toml,
                         std::string* error) {
  const size_t eol = text.find('\n');
  if (text.rfind("# ", 0) != 0 || eol == std::string_view::npos || eol <= 2) {
    *error = "settings record: the first line must be '# NAME' (the config file it stands for)";
    return false;
  }
  *config_name = std::string(text.substr(2, eol - 2));
  *toml = std::string(text.substr(eol + 1));
  return true;
}

std::string formatStrokeMapped(uint32_t stroke_index, double mapping_ms) {
  char text[96];
  std::snprintf(text, sizeof text, "stroke = %u\nmapping_ms = %.3f\n", stroke_index, mapping_ms);
  return text;
}

std::optional<StrokeMappedRecord> parseStrokeMapped(std::string_view text) {
  StrokeMappedRecord r;
  unsigned stroke = 0;
  double ms = 0.0;
  const std::string s(text);
  if (std::sscanf(s.c_str(), "stroke = %u\nmapping_ms = %lf", &stroke, &ms) != 2 || !(ms >= 0.0))
    return std::nullopt;
  r.stroke = stroke;
  r.mapping_ms = ms;
  return r;
}

std::string formatSyncMarker(const SyncMarker& m) {
  std::string label = m.label;
  for (char& c : label)
    if (c == '\n' || c == '\r') c = ' ';
  return "cloudbrush-sync v1 seq=" + std::to_string(m.seq) + " kind=" + m.kind +
         " mono_ns=" + std::to_string(m.mono_ns) + " wall_ns=" + std::to_string(m.wall_ns) +
         " label=" + label;
}

std::optional<SyncMarker> parseSyncMarker(std::string_view text) {
  if (text.rfind("cloudbrush-sync v1 ", 0) != 0) return std::nullopt;
  const std::string_view head = text.substr(0, text.find(" label="));
  SyncMarker m;
  int64_t seq = 0;
  const auto seq_text = field(head, "seq", false), kind = field(head, "kind", false),
             mono = field(head, "mono_ns", false), wall = field(head, "wall_ns", false),
             label = field(text, "label", true);
  if (!seq_text || !kind || !mono || !wall || !label || kind->empty() ||
      !parseInt64(*seq_text, &seq) || seq < 0 || !parseInt64(*mono, &m.mono_ns) ||
      !parseInt64(*wall, &m.wall_ns))
    return std::nullopt;
  m.seq = uint64_t(seq);
  m.kind = *kind;
  m.label = *label;
  return m;
}

}  // namespace cb
