#!/usr/bin/env bash
# Sets up, builds and runs the main job: the painter on a display, or (no display, no tablet)
# a headless render of the bundled cloud whose PNG and EXR paths are printed on stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
bash config/build.sh cloudbrush
exec ./build/app/cloudbrush "$@"
