// The text of the study runner's journal markers (drivers/core/JOURNAL.md "Study markers"):
// `study.EVENT word key=value key="a value with spaces"`. One place formats values and parses
// the text back (resuming a session reads its own markers, study_run_state.h).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace cb {

// `text` as a marker value: as it is when it has no space, quote, `=` or newline (and is not
// the bare word NA, which stands for a missing answer), else in double quotes with `"` and `\`
// escaped by a backslash and newlines made spaces.
std::string studyMarkerValue(const std::string& text);

struct StudyMarkerFields {
  std::string event;               // `study.EVENT`
  std::vector<std::string> words;  // bare words after it (`done`, `completed`, ...)
  std::map<std::string, std::string> values;
  std::set<std::string> quoted;  // keys whose value was quoted
  bool has(const std::string& key) const { return values.count(key) != 0; }
  std::string get(const std::string& key) const;
  // The value was the bare word NA (a missing answer), not the quoted text "NA".
  bool isNa(const std::string& key) const { return get(key) == "NA" && !quoted.count(key); }
};

StudyMarkerFields parseStudyMarker(const std::string& text);

}  // namespace cb
