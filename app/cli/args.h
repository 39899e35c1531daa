// Minimal command-line option parsing shared by every subcommand:
//   --name value, --name=value, --flag, and positional arguments.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cb {

class Args {
 public:
  // `flags` lists options that take no value (e.g. {"help", "watch"}).
  Args(int argc, char** argv, const std::vector<std::string>& flags = {"help"});

  bool has(const std::string& name) const { return options_.count(name) != 0; }
  std::optional<std::string> get(const std::string& name) const;
  std::string get(const std::string& name, const std::string& fallback) const;
  // Parses an integer/float option; on a malformed value sets error() and returns fallback.
  long getInt(const std::string& name, long fallback);
  double getDouble(const std::string& name, double fallback);
  const std::vector<std::string>& positional() const { return positional_; }
  // Options given that are not in `known` (typos), for a clear error.
  std::vector<std::string> unknown(const std::vector<std::string>& known) const;
  const std::string& error() const { return error_; }

 private:
  std::map<std::string, std::string> options_;
  std::vector<std::string> positional_;
  std::string error_;
};

}  // namespace cb
