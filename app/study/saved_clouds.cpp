#include "app/study/saved_clouds.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/core/atomic_file.h"

namespace cb {

namespace fs = std::filesystem;

bool savedCloudFiles(const std::string& journal_path, std::vector<std::string>* files,
                     std::string* error) {
  const fs::path saved = fs::path(journal_path).parent_path() / "saved";
  std::error_code ec;
  if (!fs::is_directory(saved, ec)) return true;
  for (const auto& entry : fs::directory_iterator(saved, ec))
    if (entry.is_regular_file() && entry.path().filename().string().rfind(".", 0) != 0)
      files->push_back(entry.path().string());
  if (ec) return *error = saved.string() + ": cannot list the folder: " + ec.message(), false;
  std::sort(files->begin(), files->end());
  return true;
}

bool copySavedClouds(const std::string& journal_path, const std::string& to_folder,
                     std::vector<std::string>* written, std::string* error) {
  std::vector<std::string> files;
  if (!savedCloudFiles(journal_path, &files, error)) return false;
  if (files.empty()) return true;
  std::error_code ec;
  if (!fs::is_directory(to_folder, ec)) {
    fs::create_directories(to_folder, ec);
    if (ec) return *error = to_folder + ": cannot create the folder: " + ec.message(), false;
    // The new folder's entry in its parent must reach the disk too.
    if (!syncFolderOf(to_folder, error)) return false;
  }
  for (const std::string& file : files) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (!in) return *error = file + ": cannot be read", false;
    const std::string to = (fs::path(to_folder) / fs::path(file).filename()).string();
    if (!writeFileAtomically(to, bytes.str(), error)) return false;
    if (written) written->push_back(to);
  }
  return true;
}

}  // namespace cb
