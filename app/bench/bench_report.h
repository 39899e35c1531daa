// Benchmark output: human-readable lines, then one last line of JSON
//   {"bench":"NAME","figures":{...},"baseline":{...}}
// so results can be compared over time. Baselines are measured in the same run.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace cb {

class BenchReport {
 public:
  explicit BenchReport(std::string name) : name_(std::move(name)) {}
  void figure(const std::string& key, double value) { figures_.emplace_back(key, value); }
  void baseline(const std::string& key, double value) { baseline_.emplace_back(key, value); }
  void note(const std::string& key, const std::string& text) { notes_.emplace_back(key, text); }
  // Prints the JSON line on stdout.
  void print() const;
  std::string json() const;

 private:
  std::string name_;
  std::vector<std::pair<std::string, double>> figures_, baseline_;
  std::vector<std::pair<std::string, std::string>> notes_;
};

// Wall time since t0, in ms.
double msSince(std::chrono::steady_clock::time_point t0);
// Wall time of fn(), in ms.
double timeMs(const std::function<void()>& fn);
// CPU time of the whole process so far (llvmpipe's threads included), in ms: less inflated by
// other load on the machine than wall time.
double processCpuMs();
// The process's resident set (VmRSS), in MiB; -1 when /proc cannot tell.
double processRssMb();
// Bytes as MiB.
inline double mb(size_t bytes) {
  return double(bytes) / double(1 << 20);
}

// Median of timing samples (copies; fine for benchmark sizes).
double median(std::vector<double> v);
double percentile(std::vector<double> v, double p);  // p in 0..100

}  // namespace cb
