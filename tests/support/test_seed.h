// The seed of a randomized test: CB_TEST_SEED when set (to rerun a failure exactly), else drawn
// from the clock (or, for a test whose bounds were measured on one draw, that fixed seed);
// printed always, with the line that reruns it. Header-only, so tests that link
// nothing of the app's (the power-cut writer's host side) use the same rule.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace cb::test {

inline unsigned testSeed(const char* test_name, unsigned fallback) {
  unsigned seed = fallback;
  if (const char* fixed = std::getenv("CB_TEST_SEED"))
    seed = unsigned(std::strtoul(fixed, nullptr, 10));
  std::printf("%s: seed %u (CB_TEST_SEED=%u reruns it)\n", test_name, seed, seed);
  std::fflush(stdout);
  return seed;
}

inline unsigned testSeed(const char* test_name) {
  return testSeed(test_name, unsigned(std::chrono::steady_clock::now().time_since_epoch().count()));
}

}  // namespace cb::test
