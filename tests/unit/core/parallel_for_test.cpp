#include "app/core/parallel_for.h"

#include <atomic>
#include <vector>

#include <gtest/gtest.h>

namespace cb {
namespace {

TEST(ParallelFor, VisitsEveryIndexOnceOnAnyThreadCount) {
  for (int threads : {1, 2, 8}) {
    setWorkerThreads(threads);
    std::vector<std::atomic<int>> hits(1001);
    parallelFor(hits.size(), 64, [&](size_t, size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) hits[i]++;
    });
    for (auto& h : hits) ASSERT_EQ(h.load(), 1);
  }
  setWorkerThreads(0);
}

TEST(ParallelFor, ChunkBoundariesDoNotDependOnThreads) {
  std::vector<std::vector<std::pair<size_t, size_t>>> seen;
  for (int threads : {1, 3}) {
    setWorkerThreads(threads);
    std::vector<std::pair<size_t, size_t>> chunks(chunkCount(100, 7));
    parallelFor(100, 7, [&](size_t k, size_t b, size_t e) { chunks[k] = {b, e}; });
    seen.push_back(chunks);
  }
  setWorkerThreads(0);
  EXPECT_EQ(seen[0], seen[1]);
  EXPECT_EQ(seen[0].back(), (std::pair<size_t, size_t>{98, 100}));
}

}  // namespace
}  // namespace cb
