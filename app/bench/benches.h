// One function per benchmark, each in its own bench_<name>.cpp. argv[0] is the bench name.
#pragma once

namespace cb {
int benchRender(int argc, char** argv);
int benchBrush(int argc, char** argv);
int benchMapping(int argc, char** argv);
int benchInput(int argc, char** argv);
int benchSmoothing(int argc, char** argv);
int benchHistory(int argc, char** argv);
int benchStyles(int argc, char** argv);
int benchStudy(int argc, char** argv);
int benchTools(int argc, char** argv);
int benchScale(int argc, char** argv);
int benchSky(int argc, char** argv);
int benchStrokes(int argc, char** argv);
int benchLatency(int argc, char** argv);
}  // namespace cb
