#!/usr/bin/env bash
# Installs dependencies (apt-get) and builds cloudbrush into ./build. Used by run.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash config/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j "$(nproc)"
