#include "app/bench/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>

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

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double timeMs(const std::function<void()>& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  return msSince(t0);
}

double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) / 1e6;
}

double processRssMb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return -1.0;
}

}  // namespace cb
