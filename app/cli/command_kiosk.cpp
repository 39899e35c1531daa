// `cloudbrush kiosk`: the exhibition kiosk, which is the painter with --kiosk (command_paint.cpp
// runs the one frame loop for both), `--make-attract-journal FILE`, `--set-pin`, and the error
// screen the kiosk shows instead of exiting when its config or data dir is bad.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli/command_kiosk.h"
#include "app/cli/commands.h"
#include "app/core/config_paths.h"
#include "app/kiosk/data_dir_check.h"
#include "app/kiosk/operator_pin.h"
#include "app/shell/kiosk/attract_journal.h"
#include "app/shell/frame_loop.h"
#include "app/shell/kiosk/kiosk_error_screen.h"

namespace cb {

int runKioskErrorScreen(Display& display, KioskService& service, const std::string& problem,
                        const PaintLoopOptions& options, const std::atomic<bool>* stop) {
  std::fprintf(stderr,
               "cloudbrush kiosk: CANNOT START: %s (shown on the screen until the service is "
               "restarted)\n",
               problem.c_str());
  service.onProblem(problem);
  service.onStatus("cannot start: " + problem);
  KioskCounts counts;
  counts.screen = "error";
  service.setCounts(counts);
  KioskErrorScreen screen(problem);
  FrameLoopOptions loop_options;
  loop_options.max_frames = options.max_frames;
  loop_options.max_seconds = options.max_seconds;
  loop_options.stop = stop;
  loop_options.each_iteration = [&service](bool presented) { service.onIteration(presented); };
  FrameLoop loop(display, nullptr);
  FrameLoopResult result;
  std::string error;
  const bool ran = loop.run(screen, loop_options, &result, &error);
  service.stopping();
  if (!ran) {
    std::fprintf(stderr, "cloudbrush kiosk: the error screen: %s\n", error.c_str());
    return 1;
  }
  return kKioskErrorScreenExitStatus;
}

namespace {

// Hashes the PIN read from stdin into <data dir>/operator-pin (operator_pin.h). Run as root (the
// installer), the files are given to the data dir's owner (the service's user), so that only
// root and the service can read them.
int setOperatorPin(int argc, char** argv) {
  std::string data_dir = stateDir();
  if (argc == 4 && std::string(argv[2]) == "--data-dir") {
    data_dir = argv[3];
  } else if (argc != 2) {
    std::fprintf(stderr, "usage: cloudbrush kiosk --set-pin [--data-dir DIR] < PIN\n");
    return 2;
  }
  if (::isatty(STDIN_FILENO)) std::fprintf(stderr, "operator PIN (4 to 12 digits): ");
  std::string pin;
  std::getline(std::cin, pin);
  while (!pin.empty() && (pin.back() == '\r' || pin.back() == ' ')) pin.pop_back();
  std::string error;
  if (!checkDataDir(data_dir, &error)) {
    std::fprintf(stderr, "cloudbrush kiosk: %s\n", error.c_str());
    return 1;
  }
  OperatorPinGuard guard(data_dir);
  const bool ok = guard.setPin(pin, &error);
  std::fill(pin.begin(), pin.end(), '\0');
  if (!ok) {
    std::fprintf(stderr, "cloudbrush kiosk: the PIN was not set: %s\n", error.c_str());
    return 2;
  }
  struct stat dir {};
  if (::geteuid() == 0 && ::stat(data_dir.c_str(), &dir) == 0 && dir.st_uid != 0)
    for (const char* name : {OperatorPinGuard::kPinFile, OperatorPinGuard::kLockoutFile})
      if (::chown((data_dir + "/" + name).c_str(), dir.st_uid, dir.st_gid) != 0)
        std::fprintf(stderr, "cloudbrush kiosk: chown %s/%s: %s\n", data_dir.c_str(), name,
                     std::strerror(errno));
  std::printf("the operator PIN is set (%s/%s, hashed, mode 0600)\n", data_dir.c_str(),
              OperatorPinGuard::kPinFile);
  return 0;
}

}  // namespace

int commandKiosk(int argc, char** argv) {
  // `cloudbrush kiosk --make-attract-journal FILE` writes the bundled attract journal
  // (config/kiosk/attract.cbj; app/shell/kiosk/attract_journal.h).
  if (argc == 3 && std::string(argv[1]) == "--make-attract-journal") {
    std::string error;
    if (!writeAttractJournal(argv[2], &error)) {
      std::fprintf(stderr, "cloudbrush kiosk: %s\n", error.c_str());
      return 1;
    }
    std::printf("%s\n", argv[2]);
    return 0;
  }
  // `cloudbrush kiosk --set-pin [--data-dir DIR]`: the operator PIN from stdin (one line).
  if (argc >= 2 && std::string(argv[1]) == "--set-pin") return setOperatorPin(argc, argv);
  // The painter with --kiosk: one frame loop and one set of options for both.
  std::vector<char*> args(argv, argv + argc);
  static char kiosk_flag[] = "--kiosk";
  args.insert(args.begin() + 1, kiosk_flag);
  return commandPaint(int(args.size()), args.data());
}

}  // namespace cb
