// `cloudbrush kiosk`: the exhibition kiosk, which is the painter with --kiosk (command_paint.cpp
// runs the one frame loop for both), and `--make-attract-journal FILE`.
#include <cstdio>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/shell/attract_journal.h"

namespace cb {

int commandKiosk(int argc, char** argv) {
  // `cloudbrush kiosk --make-attract-journal FILE` writes the bundled attract journal
  // (config/kiosk/attract.cbj; app/shell/attract_journal.h).
  if (argc == 3 && std::string(argv[1]) == "--make-attract-journal") {
    std::string error;
    if (!writeAttractJournal(argv[2], &error)) {
      std::fprintf(stderr, "cloudbrush kiosk: %s\n", error.c_str());
      return 1;
    }
    std::printf("%s\n", argv[2]);
    return 0;
  }
  // The painter with --kiosk: one frame loop and one set of options for both.
  std::vector<char*> args(argv, argv + argc);
  static char kiosk_flag[] = "--kiosk";
  args.insert(args.begin() + 1, kiosk_flag);
  return commandPaint(int(args.size()), args.data());
}

}  // namespace cb
