#include "app/study/study_marker_text.h"

namespace cb {

std::string studyMarkerValue(const std::string& text) {
  if (!text.empty() && text != "NA" && text.find_first_of(" \"=\n") == std::string::npos)
    return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c == '\n' ? ' ' : c;
  }
  return out + "\"";
}

std::string StudyMarkerFields::get(const std::string& key) const {
  const auto it = values.find(key);
  return it == values.end() ? std::string() : it->second;
}

StudyMarkerFields parseStudyMarker(const std::string& text) {
  StudyMarkerFields m;
  size_t i = 0;
  // One token up to a space or `=`; quoted parts lose their quotes and escapes.
  const auto token = [&](bool* was_quoted) {
    std::string out;
    *was_quoted = false;
    while (i < text.size() && text[i] != ' ' && text[i] != '=') {
      if (text[i] != '"') {
        out += text[i++];
        continue;
      }
      *was_quoted = true;
      for (++i; i < text.size() && text[i] != '"'; ++i) {
        if (text[i] == '\\' && i + 1 < text.size()) ++i;
        out += text[i];
      }
      if (i < text.size()) ++i;  // the closing quote
    }
    return out;
  };
  bool first = true;
  while (i < text.size()) {
    if (text[i] == ' ') {
      ++i;
      continue;
    }
    bool key_quoted = false;
    const std::string key = token(&key_quoted);
    if (i < text.size() && text[i] == '=') {
      ++i;
      bool value_quoted = false;
      m.values[key] = token(&value_quoted);
      if (value_quoted) m.quoted.insert(key);
    } else if (first) {
      m.event = key;
    } else {
      m.words.push_back(key);
    }
    first = false;
  }
  return m;
}

}  // namespace cb
