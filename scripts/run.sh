#!/usr/bin/env bash
# The README's main command: installs what is missing, builds, and runs the main job: the batch
# precision table of the embedded default scene (Gilg et al. 2021: 7 techniques x float32,
# unorm24, 30 distances, 100 frames, 200x200 kernel). Extra arguments go to `depthprec table`.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
build/depthprec devices
build/depthprec table "$@"
