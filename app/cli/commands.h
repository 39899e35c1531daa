// Entry points of the cloudbrush subcommands. argv[0] is the subcommand name; each command
// handles --help itself and returns the process exit code.
#pragma once

namespace cb {

int commandPaint(int argc, char** argv);      // default: painter on a display, else headless render
int commandKiosk(int argc, char** argv);      // the painter as an exhibition kiosk (service)
int commandRender(int argc, char** argv);     // offline render of a saved volume
int commandDevices(int argc, char** argv);    // list pens, --watch prints live samples
int commandCalibrate(int argc, char** argv);  // N-point pen calibration
int commandReplay(int argc, char** argv);     // re-run a session journal headlessly
int commandBench(int argc, char** argv);      // bench NAME
int commandStudy(int argc, char** argv);      // study export | volume | report

}  // namespace cb
