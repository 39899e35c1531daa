#include "app/cli/args.h"

#include <algorithm>
#include <cstdlib>

namespace cb {

Args::Args(int argc, char** argv, const std::vector<std::string>& flags) {
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0 || a.size() == 2) {
      positional_.push_back(a);
      continue;
    }
    std::string name = a.substr(2);
    auto eq = name.find('=');
    if (eq != std::string::npos) {
      options_[name.substr(0, eq)] = name.substr(eq + 1);
    } else if (std::find(flags.begin(), flags.end(), name) != flags.end() || i + 1 >= argc) {
      options_[name] = "";
    } else {
      options_[name] = argv[++i];
    }
  }
}

std::optional<std::string> Args::get(const std::string& name) const {
  auto it = options_.find(name);
  if (it == options_.end()) return std::nullopt;
  return it->second;
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  return get(name).value_or(fallback);
}

long Args::getInt(const std::string& name, long fallback) {
  auto v = get(name);
  if (!v) return fallback;
  char* end = nullptr;
  long r = std::strtol(v->c_str(), &end, 10);
  if (v->empty() || *end != 0) {
    error_ = "--" + name + ": expected an integer, got '" + *v + "'";
    return fallback;
  }
  return r;
}

double Args::getDouble(const std::string& name, double fallback) {
  auto v = get(name);
  if (!v) return fallback;
  char* end = nullptr;
  double r = std::strtod(v->c_str(), &end);
  if (v->empty() || *end != 0) {
    error_ = "--" + name + ": expected a number, got '" + *v + "'";
    return fallback;
  }
  return r;
}

std::vector<std::string> Args::unknown(const std::vector<std::string>& known) const {
  std::vector<std::string> out;
  for (auto& [k, v] : options_)
    if (std::find(known.begin(), known.end(), k) == known.end()) out.push_back("--" + k);
  return out;
}

}  // namespace cb
