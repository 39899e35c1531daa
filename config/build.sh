#!/usr/bin/env bash
# Installs dependencies (apt-get) and builds into ./build: the targets named as arguments (run.sh
# builds only `cloudbrush`), or everything (test.sh, packaging). Used by run.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash config/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j "$(nproc)" ${1:+--target "$@"}
