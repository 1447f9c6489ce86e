#!/usr/bin/env bash
# Builds a libFuzzer target with clang (ASan + UBSan) in build-fuzz/ and runs it for the given
# number of seconds (default 600): scene (scene files, seeded with data/), journal (row journals
# as --resume reads them) or shard (JSON outputs as merge and compare read them), each seeded from
# tests/fuzz/seeds/. Crashes are written to build-fuzz/crashes/TARGET/; each one becomes a
# regression test, tagged [fuzz] (tests/model/scene.cpp, tests/analysis/compare.cpp,
# tests/cli/cli_mts.cpp; the inputs kept in tests/fuzz/regressions/). docs/fuzzing.md.
# Usage: scripts/fuzz.sh [scene|journal|shard] [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
target=scene
if [ $# -gt 0 ] && [[ ! "$1" =~ ^[0-9]+$ ]]; then target="$1"; shift; fi
seconds="${1:-600}"
case "$target" in scene | journal | shard) ;; *)
  echo "fuzz.sh: unknown target '$target' (scene, journal or shard)" >&2; exit 2 ;;
esac
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
cmake --build build-fuzz -j "$(nproc)" --target "${target}_fuzzer"
corpus=build-fuzz/corpus/$target crashes=build-fuzz/crashes/$target
mkdir -p "$corpus" "$crashes"
if [ "$target" = scene ]; then seeds=data; else seeds=tests/fuzz/seeds/$target; fi
cp -n "$seeds"/* "$corpus"/ 2>/dev/null || true
"build-fuzz/tests/fuzz/${target}_fuzzer" "$corpus" -max_total_time="$seconds" -max_len=16384 \
  -artifact_prefix="$crashes/" -print_final_stats=1
