#include "app/bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cb {
namespace {

std::string quote(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') {
      o += "\\n";
      continue;
    }
    o += c;
  }
  return o + "\"";
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  char b[64];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

template <typename T, typename F>
std::string object(const std::vector<std::pair<std::string, T>>& kv, F fmt) {
  std::string o = "{";
  for (size_t i = 0; i < kv.size(); ++i)
    o += (i ? "," : "") + quote(kv[i].first) + ":" + fmt(kv[i].second);
  return o + "}";
}

}  // namespace

std::string BenchReport::json() const {
  std::string o = "{\"bench\":" + quote(name_) + ",\"figures\":" + object(figures_, number) +
                  ",\"baseline\":" + object(baseline_, number);
  if (!notes_.empty()) o += ",\"notes\":" + object(notes_, quote);
  return o + "}";
}

void BenchReport::print() const {
  std::printf("%s\n", json().c_str());
  std::fflush(stdout);
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  double pos = p / 100.0 * double(v.size() - 1);
  size_t i = size_t(pos);
  double f = pos - double(i);
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

double median(std::vector<double> v) {
  return percentile(std::move(v), 50.0);
}

}  // namespace cb
