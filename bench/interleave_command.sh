#!/bin/sh
# Two depthprec binaries running the same command alternately (A, B, A, B, ...), so that this VM's
# drift falls on both alike: prints each one's median and fastest wall time and median CPU time
# (user + system) over the rounds.
# Usage: bench/interleave_command.sh rounds binary_A binary_B [depthprec arguments]
#   e.g. bench/interleave_command.sh 5 /tmp/old/depthprec build/depthprec table --no-timing -q -o /tmp/t.csv
set -eu
rounds=$1 a=$2 b=$3
shift 3
out=$(mktemp)
times=$(mktemp)
trap 'rm -f "$out" "$times"' EXIT
i=0
while [ "$i" -lt "$rounds" ]; do
  for which in A B; do
    bin=$a
    [ "$which" = B ] && bin=$b
    /usr/bin/time -f "$which %e %U %S" -o "$times" "$bin" "$@" > /dev/null
    cat "$times" >> "$out"
  done
  i=$((i + 1))
done
# the median of column $2 (wall, or cpu = user + system) of binary $1
median() {
  awk -v w="$1" -v c="$2" '$1 == w { print (c == "wall") ? $2 : $3 + $4 }' "$out" | sort -g |
    awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
for which in A B; do
  fastest=$(awk -v w="$which" '$1 == w { print $2 }' "$out" | sort -g | head -1)
  printf '%s wall median %.2f s, fastest %.2f s; cpu median %.2f s\n' "$which" \
    "$(median "$which" wall)" "$fastest" "$(median "$which" cpu)"
done
