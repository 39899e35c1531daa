#include "app/kiosk/health_file_writer.h"

#include <chrono>
#include <filesystem>

#include "app/kiosk/atomic_file.h"
#include "app/kiosk/disk_space.h"

namespace cb {

HealthFileWriter::HealthFileWriter(std::string data_dir, const HealthTracker& tracker,
                                   const Clock& clock, int64_t interval_ns,
                                   std::function<int64_t()> wall_clock)
    : data_dir_(std::move(data_dir)),
      tracker_(tracker),
      clock_(clock),
      interval_ns_(interval_ns),
      wall_clock_(std::move(wall_clock)) {
  if (!wall_clock_) {
    wall_clock_ = [] {
      return static_cast<int64_t>(std::chrono::duration_cast<std::chrono::seconds>(
                                      std::chrono::system_clock::now().time_since_epoch())
                                      .count());
    };
  }
}

std::string HealthFileWriter::path() const {
  return (std::filesystem::path(data_dir_) / kFileName).string();
}

bool HealthFileWriter::writeIfDue(std::string* error) {
  if (written_ && clock_.nowNs() - last_write_ns_ < interval_ns_) return true;
  return write(error);
}

bool HealthFileWriter::write(std::string* error) {
  const int64_t now = clock_.nowNs();
  std::error_code ec;
  std::filesystem::create_directories(data_dir_, ec);
  if (ec) {
    if (error) *error = data_dir_ + ": cannot create the data directory: " + ec.message();
    return false;
  }
  std::optional<DiskSpace> disk = diskSpaceAt(data_dir_, nullptr);
  const HealthStatus status = tracker_.snapshot(disk ? &*disk : nullptr, wall_clock_());
  if (!writeFileAtomically(path(), healthStatusJson(status), error)) return false;
  written_ = true;
  last_write_ns_ = now;
  return true;
}

}  // namespace cb
