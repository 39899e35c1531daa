#include "app/kiosk/data_retention.h"

#include <chrono>

namespace cb {
namespace fs = std::filesystem;

std::vector<std::string> deleteFilesOlderThan(const std::string& dir, const std::string& extension,
                                              double keep_days, fs::file_time_type now,
                                              std::string* error) {
  std::vector<std::string> deleted;
  const auto max_age = std::chrono::duration_cast<fs::file_time_type::duration>(
      std::chrono::duration<double>(keep_days * 86400.0));
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return deleted;
  for (const auto& item : fs::directory_iterator(dir, ec)) {
    std::error_code item_ec;
    if (!item.is_regular_file(item_ec) || item.path().extension() != extension) continue;
    const auto written = item.last_write_time(item_ec);
    if (item_ec || now - written <= max_age) continue;
    if (fs::remove(item.path(), item_ec))
      deleted.push_back(item.path().string());
    else if (item_ec && error->empty())
      *error = item.path().string() + ": " + item_ec.message();
  }
  if (ec && error->empty()) *error = dir + ": " + ec.message();
  return deleted;
}

}  // namespace cb
