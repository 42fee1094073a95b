#!/usr/bin/env bash
# Surface formats benchmark (issue 13): read time (median of REPEATS) and peak RSS of an N x N surface
# in each format, each format in its own process. Prints CSV with the ratio of each to .npy:
# format,n,repeats,median_s,min_s,peak_rss_mib,field_mib,time_ratio_to_npy,rss_ratio_to_npy
#   bench/run_formats.sh [N (4096)] [REPEATS (5)]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
n=${1:-4096}
repeats=${2:-5}
cmake --build "$build" --target bench_formats >/dev/null
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$build/bench_formats" "$n" 1 "$dir" write
ls -l "$dir" >&2
for format in npy nc x3p sdf gsf; do
  "$build/bench_formats" "$n" "$repeats" "$dir" "$format"
done | awk -F, 'BEGIN { print "format,n,repeats,median_s,min_s,peak_rss_mib,field_mib,time_ratio_to_npy,rss_ratio_to_npy" }
  $1 == "npy" { t = $4; m = $6 } { printf "%s,%.2f,%.2f\n", $0, $4 / t, $6 / m }'
