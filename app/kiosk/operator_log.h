// The operator's actions, one line each, appended to <data dir>/operator.log (and echoed to
// stderr, so journalctl has them too): UTC wall time, then the action and its details, e.g.
//   2026-11-23T01:02:03Z panel-opened
//   2026-11-23T01:02:09Z set idle_seconds=105
// Failed PIN attempts are logged as well. The file is opened, appended and closed per line.
#pragma once

#include <string>

namespace cb {

class OperatorLog {
 public:
  explicit OperatorLog(std::string path) : path_(std::move(path)) {}
  const std::string& path() const { return path_; }
  // False with *error naming the file when the line could not be written (it is still echoed).
  bool write(const std::string& action, std::string* error) const;

 private:
  std::string path_;
};

}  // namespace cb
