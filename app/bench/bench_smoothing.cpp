// PLACEHOLDER: replaced by the capability that implements it.
#include <cstdio>

#include "app/bench/benches.h"

namespace cb {
int benchSmoothing(int, char**) {
  std::fprintf(stderr, "cloudbrush: this command is not built yet\n");
  return 3;
}
}  // namespace cb
