#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and runs the main job on the
# embedded default scene. Extra arguments go to depthprec.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
build/depthprec devices
build/depthprec formats --value 0.5 --value 0.999 --on-device "$@"
