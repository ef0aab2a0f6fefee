#!/bin/bash
# Two builds of isolux-bench timed in alternation (A, B, A, B, ...), so a
# load on the shared host that comes and goes hits both: docs/performance.md's
# "alternating runs of two builds".
#
#   bash scripts/alternate.sh A B filter [rounds]
#
# A and B: two isolux-bench binaries (e.g. copies built before and after a
# change); filter: a --benchmark_filter regex; rounds: how many times each
# runs (default 5), each with --benchmark_repetitions=3. Prints, per side and
# benchmark, the fastest and the mean of the rounds' medians (the bench's
# time unit), and the mean of the rounds' medians of each stage counter the
# benchmark reports (blur_ms=, composite_ms=, ...: whole_frame/*).
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: alternate.sh A B filter [rounds]" >&2; exit 2; }
a=$1 b=$2 filter=$3 rounds=${4:-5}
for bin in "$a" "$b"; do [ -x "$bin" ] || { echo "alternate: $bin is not an executable" >&2; exit 2; }; done
for _ in $(seq "$rounds"); do
  for side in A B; do
    bin=$a; [ "$side" = B ] && bin=$b
    "$bin" --benchmark_filter="$filter" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true 2> /dev/null |
      awk -v side="$side" '$1 ~ /_median$/ {
        sub(/_median$/, "", $1); print side, $1, $2
        for (i = 3; i <= NF; i++) if ($i ~ /^[a-z_]+_ms=/) { split($i, kv, "="); print side, $1 "[" kv[1] "]", kv[2] }
      }'
  done
done | awk '{ k = $1 " " $2; if (!(k in low) || $3 < low[k]) low[k] = $3; sum[k] += $3; n[k]++ }
            END { for (k in low) printf "%-62s fastest %.4f mean %.4f\n", k, low[k], sum[k] / n[k] }' | sort -k2,2 -k1,1
