#include "app/core/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <thread>
#include <vector>

namespace cb {
namespace {
std::atomic<int> g_override{0};
}

int workerThreads() {
  if (int o = g_override.load()) return o;
  if (const char* e = std::getenv("CLOUDBRUSH_THREADS")) {
    int n = std::atoi(e);
    if (n > 0) return n;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

void setWorkerThreads(int n) {
  g_override.store(std::max(0, n));
}

void parallelFor(size_t n, size_t grain, const std::function<void(size_t, size_t, size_t)>& fn) {
  if (n == 0) return;
  grain = std::max<size_t>(1, grain);
  const size_t chunks = chunkCount(n, grain);
  const size_t threads = std::min<size_t>(size_t(workerThreads()), chunks);
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (size_t k; (k = next.fetch_add(1)) < chunks;)
      fn(k, k * grain, std::min(n, (k + 1) * grain));
  };
  if (threads <= 1) {
    worker();
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (size_t i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

}  // namespace cb
