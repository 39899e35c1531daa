#include "tests/layering/layering_rules.h"

#include <regex>
#include <sstream>

namespace cb::layering {
namespace {

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

std::string roomOf(const std::string& path) {
  for (const char* top : {"app/", "drivers/"}) {
    if (!startsWith(path, top)) continue;
    const size_t slash = path.find('/', std::string(top).size());
    // A file directly under app/ or drivers/ (main.cpp, open_pen_source.cpp) is its own folder.
    return slash == std::string::npos ? std::string(top, std::string(top).size() - 1)
                                      : path.substr(0, slash);
  }
  for (const char* top : {"calibration/", "shaders/"})
    if (startsWith(path, top)) return std::string(top, std::string(top).size() - 1);
  return "";
}

std::vector<std::string> allowedPrefixes(const std::string& text) {
  std::vector<std::string> prefixes;
  static const std::regex kTick("`([A-Za-z0-9_./]+)`");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), kTick);
       it != std::sregex_iterator(); ++it) {
    std::string token = (*it)[1];
    while (!token.empty() && token.back() == '/') token.pop_back();
    if (token.empty()) continue;
    const bool top = token == "app" || startsWith(token, "drivers") ||
                     startsWith(token, "calibration") || startsWith(token, "shaders");
    std::string prefix = top ? token : "app/" + token;
    const bool is_file = prefix.size() > 2 && (prefix.substr(prefix.size() - 2) == ".h");
    if (!is_file) prefix += '/';
    prefixes.push_back(prefix);
  }
  return prefixes;
}

std::map<std::string, std::vector<std::string>> appTable(const std::string& readme_text) {
  std::map<std::string, std::vector<std::string>> table;
  std::istringstream lines(readme_text);
  std::string line;
  // | folder/ | what | may include |
  static const std::regex kRow(R"(^\|\s*([a-z_]+)/\s*\|.*\|([^|]*)\|\s*$)");
  while (std::getline(lines, line)) {
    std::smatch row;
    if (std::regex_match(line, row, kRow)) table["app/" + row[1].str()] = allowedPrefixes(row[2]);
  }
  return table;
}

std::string mayIncludeParagraph(const std::string& readme_text) {
  size_t start = readme_text.find("May include:");
  if (start == std::string::npos) start = readme_text.find("May depend on:");
  if (start == std::string::npos) return "";
  size_t end = readme_text.find("\n\n", start);
  std::string paragraph = readme_text.substr(start, end == std::string::npos ? end : end - start);
  for (const char* refusal : {"Nothing", "Never", "Must not"}) {
    const size_t cut = paragraph.find(refusal);
    if (cut != std::string::npos) paragraph.resize(cut);
  }
  return paragraph;
}

std::vector<Include> projectIncludes(const std::string& file, const std::string& text) {
  std::vector<Include> includes;
  static const std::regex kInclude(R"(^\s*#\s*include\s+"([^"]+)\")");
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    std::smatch match;
    if (std::regex_search(line, match, kInclude) && !roomOf(match[1]).empty())
      includes.push_back({file, number, match[1]});
  }
  return includes;
}

bool allowed(const Include& include, const std::map<std::string, std::vector<std::string>>& rules) {
  const std::string from = roomOf(include.file);
  const std::string to = roomOf(include.target);
  if (from == to) return true;
  // app/main.cpp and drivers/open_pen_source.cpp sit over their own subfolders.
  if ((from == "app" || from == "drivers") && startsWith(include.target, from + "/")) return true;
  const auto rule = rules.find(from);
  if (rule == rules.end()) return false;
  for (const std::string& prefix : rule->second)
    if (prefix.back() == '/' ? startsWith(include.target, prefix) : include.target == prefix)
      return true;
  return false;
}

}  // namespace cb::layering
