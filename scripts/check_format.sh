#!/usr/bin/env bash
# Fails when a C++ or OpenCL source is not formatted as .clang-format says (clang-format from
# Debian, installed by scripts/setup.sh). Run by ctest as the test `clang_format`; to fix:
#   find formats kernels host tests bench \( -name '*.cpp' -o -name '*.h' -o -name '*.cl' \) | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(find formats kernels host tests bench \( -name '*.cpp' -o -name '*.h' -o -name '*.cl' \) | sort)
if clang-format --dry-run --Werror "${files[@]}"; then
  echo "clang-format: ${#files[@]} files formatted"
else
  echo "clang-format: the files above differ from .clang-format (fix with clang-format -i)" >&2
  exit 1
fi
