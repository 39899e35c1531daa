#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (unit, golden images on llvmpipe, the virtual
# tablet in qemu). Long checks labelled `slow` are excluded; run them with
#   ctest --test-dir build -L slow --output-on-failure
set -euo pipefail
cd "$(dirname "$0")/.."
bash config/build.sh
export LIBGL_ALWAYS_SOFTWARE=1
ctest --test-dir build -LE slow --output-on-failure -j "$(nproc)" "$@"
