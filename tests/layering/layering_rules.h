// The project's layering as its READMEs state it, read from the text so the READMEs stay the one
// place it is written: app/README.md's table (folder → what it may include) and the "May
// include:" / "May depend on:" paragraph of each drivers/*/README.md and calibration/README.md.
// Project folders and files are named in backticks there: `scene` is app/scene/, `drivers/core`
// and `calibration` are top-level folders, `render/image_io.h` is that one file, `app` is every
// app folder. Text after "Nothing", "Never" or "Must not" in a paragraph names what is refused.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace cb::layering {

// The folder an include path belongs to: app/X, drivers/X, calibration or shaders ("" for
// anything else, e.g. a system header). Files directly in app/ or drivers/ are their own folder.
std::string roomOf(const std::string& path);

// Backticked tokens as include-path prefixes: `scene` → "app/scene/", `render/image_io.h` →
// "app/render/image_io.h", `drivers/core` → "drivers/core/", `app` → "app/".
std::vector<std::string> allowedPrefixes(const std::string& may_include_text);

// app/README.md's table: "app/X" → allowed prefixes.
std::map<std::string, std::vector<std::string>> appTable(const std::string& readme_text);

// A README's "May include:" (or "May depend on:") paragraph up to "Nothing"/"Never"/"Must not".
std::string mayIncludeParagraph(const std::string& readme_text);

struct Include {
  std::string file;    // the including file, relative to the source root
  int line = 0;        // 1-based
  std::string target;  // the quoted include path
};

// The quoted #include lines of a file's text that name a project folder.
std::vector<Include> projectIncludes(const std::string& file, const std::string& text);

// Whether `include` is allowed: within its own folder (app/render/gl counts as app/render), from a
// top-level file (app/main.cpp, drivers/open_pen_source.cpp) into its own tree, or by a prefix
// of the including folder's rule. Folders without a rule allow nothing outside themselves.
bool allowed(const Include& include, const std::map<std::string, std::vector<std::string>>& rules);

}  // namespace cb::layering
