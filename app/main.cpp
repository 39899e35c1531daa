// cloudbrush: paint volumetric clouds with a pen. One binary, one command line (see README).
#include <cstdio>
#include <cstring>
#include <string>

#include "app/cli/commands.h"

namespace {

struct Command {
  const char* name;
  const char* summary;
  int (*run)(int, char**);
};

const Command kCommands[] = {
    {"paint", "the interactive painter (the default; headless render without a display)",
     cb::commandPaint},
    {"kiosk", "the painter as an exhibition kiosk: visitor mode, idle reset, systemd watchdog",
     cb::commandKiosk},
    {"render", "render a saved volume offline to PNG/EXR", cb::commandRender},
    {"devices", "list pen devices; --watch prints live samples", cb::commandDevices},
    {"calibrate", "pen-driven N-point calibration of the tablet-to-screen mapping",
     cb::commandCalibrate},
    {"replay", "re-run a recorded session journal headlessly (volume checksum, render)",
     cb::commandReplay},
    {"study", "user-study exports (InkML, CSV, VDB, EXR) and the questionnaire report",
     cb::commandStudy},
    {"bench", "run a benchmark: bench NAME (bench --help lists them)", cb::commandBench},
};

void printUsage() {
  std::printf("usage: cloudbrush [COMMAND] [OPTIONS]\n\ncommands:\n");
  for (const Command& c : kCommands) std::printf("  %-10s %s\n", c.name, c.summary);
  std::printf("\nWith no command, runs 'paint'. Each command takes --help.\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && argv[1][0] != '-') {
    for (const Command& c : kCommands)
      if (std::strcmp(argv[1], c.name) == 0) return c.run(argc - 1, argv + 1);
    std::fprintf(stderr, "cloudbrush: unknown command '%s'\n\n", argv[1]);
    printUsage();
    return 2;
  }
  if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    printUsage();
    return 0;
  }
  static char paint[] = "paint";
  argv[0] = paint;
  return cb::commandPaint(argc, argv);
}
