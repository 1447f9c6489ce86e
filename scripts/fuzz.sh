#!/usr/bin/env bash
# Builds the libFuzzer scene target with clang (ASan + UBSan) in build-fuzz/ and runs it for the
# given number of seconds (default 600), seeded with the scenes in data/. Crashes are written to
# build-fuzz/crashes/; each one becomes a case of "fuzzer regressions end in input errors" in tests/test_scene.cpp.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
scripts/setup.sh
missing=()
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
CXX=clang++ CC=clang cmake -S . -B build-fuzz -DDEPTHPREC_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz -j "$(nproc)" --target scene_fuzzer
mkdir -p build-fuzz/corpus build-fuzz/crashes
cp -n data/*.json build-fuzz/corpus/ 2>/dev/null || true
build-fuzz/tests/fuzz/scene_fuzzer build-fuzz/corpus -max_total_time="$seconds" -max_len=8192 \
  -artifact_prefix=build-fuzz/crashes/ -print_final_stats=1
