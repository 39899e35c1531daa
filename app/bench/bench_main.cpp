// `cloudbrush bench NAME`: benchmarks shipped in the product so an installer can check a kiosk
// machine. Each prints figures and ends with one JSON line (bench_report.h). Never fails on a
// missed target; exit code is non-zero only when the benchmark could not run.
#include <cstdio>
#include <cstring>

#include "app/bench/benches.h"
#include "app/cli/commands.h"

namespace cb {
namespace {

struct Bench {
  const char* name;
  const char* summary;
  int (*run)(int, char**);
};

const Bench kBenches[] = {
    {"render", "frame time with/without empty-space skipping, light volume, vs vdb_render",
     benchRender},
    {"brush", "cost per pen sample for each brush at 200 Hz", benchBrush},
    {"mapping", "hybrid mapping stages and pen-up to lit frame", benchMapping},
    {"input", "report decode cost and kernel-to-consumer delay", benchInput},
    {"smoothing", "jitter and lag of raw, moving average and 1-euro filtering; prediction",
     benchSmoothing},
    {"history", "undo/redo, erase and light to restored volume and lit frame; history bytes",
     benchHistory},
    {"styles", "each render style's full frame against the thesis style's", benchStyles},
    {"study", "study exports (256^3 volume as VDB and raw, EXR+PNG) and report for 20 sessions",
     benchStudy},
    {"tools", "picture -> cloud, model -> cloud, morph in-betweens, each vs a baseline",
     benchTools},
    {"scale", "1280x720 .. 3840x2160 on 1 and 2 threads: frame, orbit, painting, pen-up",
     benchScale},
    {"sky", "the sparse volume's bytes for 1x, 4x, 16x sky area, against the dense grid", benchSky},
    {"strokes", "the stroke gallery at product defaults; --sheet: strokes x styles contact sheet",
     benchStrokes},
    {"latency", "pen sample -> frame ready / present while painting, vs today's loop",
     benchLatency},
};

}  // namespace

int commandBench(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0) {
    std::printf("usage: cloudbrush bench NAME [OPTIONS]\n\nbenchmarks:\n");
    for (const Bench& b : kBenches) std::printf("  %-10s %s\n", b.name, b.summary);
    return argc < 2 ? 2 : 0;
  }
  for (const Bench& b : kBenches)
    if (std::strcmp(argv[1], b.name) == 0) return b.run(argc - 1, argv + 1);
  std::fprintf(stderr, "cloudbrush bench: unknown benchmark '%s' (see bench --help)\n", argv[1]);
  return 2;
}

}  // namespace cb
