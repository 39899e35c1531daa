#include "app/kiosk/unsaved_visit.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "app/core/atomic_file.h"

namespace cb {

std::string unsavedVisitPath(const std::string& data_dir) {
  return data_dir + "/unsaved-visit";
}

bool writeUnsavedVisit(const std::string& data_dir, const UnsavedVisit& visit, std::string* error) {
  std::string text = "journal = " + visit.journal + "\n";
  if (visit.gallery_newest_before)
    text += "gallery_newest_before = " + std::to_string(*visit.gallery_newest_before) + "\n";
  return writeFileAtomically(unsavedVisitPath(data_dir), text, error);
}

std::optional<UnsavedVisit> readUnsavedVisit(const std::string& data_dir, std::string* error) {
  const std::string path = unsavedVisitPath(data_dir);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec) && !ec) return std::nullopt;
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot be read: " + std::strerror(errno);
    return std::nullopt;
  }
  UnsavedVisit visit;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const size_t eq = line.find(" = ");
    const std::string key = line.substr(0, eq),
                      value = eq == std::string::npos ? "" : line.substr(eq + 3);
    const std::string where = path + ":" + std::to_string(n) + ": ";
    if (key == "journal" && !value.empty() && value.find('/') == std::string::npos) {
      visit.journal = value;
    } else if (key == "gallery_newest_before") {
      char* end = nullptr;
      const long number = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || number < 0) {
        *error = where + "gallery_newest_before: not an entry number: '" + value + "'";
        return std::nullopt;
      }
      visit.gallery_newest_before = number;
    } else {
      *error = where + (key == "journal" ? "journal: not a file name: '" + value + "'"
                                         : "not 'journal = NAME' or 'gallery_newest_before = N'");
      return std::nullopt;
    }
  }
  if (visit.journal.empty()) {
    *error = path + ":1: journal: missing";
    return std::nullopt;
  }
  return visit;
}

bool clearUnsavedVisit(const std::string& data_dir, std::string* error) {
  const std::string path = unsavedVisitPath(data_dir);
  std::error_code ec;
  std::filesystem::remove(path, ec);
  if (ec) {
    *error = path + ": cannot be removed: " + ec.message();
    return false;
  }
  return syncFolderOf(path, error);
}

}  // namespace cb
