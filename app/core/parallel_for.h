// Deterministic parallel loops. Work over [0, n) is cut into chunks whose boundaries depend only
// on n and the grain, never on the thread count, so a caller that reduces per-chunk results in
// chunk order gets the same bytes on 1, 2 or 64 threads.
#pragma once

#include <cstddef>
#include <functional>

namespace cb {

// Threads used by parallelFor: CLOUDBRUSH_THREADS if set, else the hardware concurrency.
int workerThreads();
// Overrides the thread count for this process (tests use 1, 2 and 8). 0 restores the default.
void setWorkerThreads(int n);

// Calls fn(chunk_index, begin, end) for chunks [k*grain, min(n,(k+1)*grain)). Blocks until all
// chunks are done. fn must only write state owned by its chunk.
void parallelFor(size_t n, size_t grain, const std::function<void(size_t, size_t, size_t)>& fn);

inline size_t chunkCount(size_t n, size_t grain) {
  return grain ? (n + grain - 1) / grain : 0;
}

}  // namespace cb
