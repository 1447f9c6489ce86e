#!/usr/bin/env bash
# The README's test command: installs what is missing, builds, runs the whole test suite in
# parallel (ctest -j), including the exhaustive storage-format proof, and prints its counts.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
ctest --test-dir build -j "$(nproc)" --output-on-failure "$@"
grep -h '^exhaustive ' build/Testing/Temporary/LastTest.log 2>/dev/null || true
