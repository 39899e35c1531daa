#include "app/kiosk/health_file_writer.h"

#include <chrono>
#include <filesystem>

#include "app/kiosk/disk_space.h"
#include "app/kiosk/metrics_text.h"
#include "app/kiosk/reserved_file.h"

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

std::string HealthFileWriter::metricsPath() const {
  return metrics_dir_.empty() ? ""
                              : (std::filesystem::path(metrics_dir_) / "cloudbrush.prom").string();
}

bool HealthFileWriter::writeIfDue(std::string* error) {
  if (written_ && clock_.nowNs() - last_write_ns_ < interval_ns_) {
    if (!last_error_.empty() && error) *error = last_error_;
    return last_error_.empty();
  }
  std::string write_error;
  const bool ok = write(&write_error);
  last_error_ = ok ? "" : write_error;
  if (!ok && error) *error = write_error;
  return ok;
}

bool HealthFileWriter::write(std::string* error) {
  written_ = true;
  last_write_ns_ = clock_.nowNs();
  std::error_code ec;
  std::filesystem::create_directories(data_dir_, ec);
  std::optional<DiskSpace> disk = diskSpaceAt(data_dir_, nullptr);
  const HealthStatus status = tracker_.snapshot(disk ? &*disk : nullptr, wall_clock_());
  std::string metrics_error;
  const bool metrics_ok =
      metrics_dir_.empty() ||
      writeFileKeepingBlocks(metricsPath(), metricsText(status, CB_VERSION), &metrics_error);
  if (ec) {
    if (error) *error = data_dir_ + ": cannot create the data directory: " + ec.message();
    return false;
  }
  // Through a spare copy whose blocks are kept: on a disk something else filled to the last
  // byte, the health file still says so (reserved_file.h).
  if (!writeFileKeepingBlocks(path(), healthStatusJson(status), error)) return false;
  if (!metrics_ok && error) *error = metrics_error;
  return metrics_ok;
}

}  // namespace cb
