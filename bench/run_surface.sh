#!/usr/bin/env bash
# Surface synthesis benchmark: 512^2 .. 8192^2 at 1 and 2 threads. Prints CSV:
# n,threads,repeats,median_s,c2r_floor_s,ratio_to_floor,peak_rss_mib,model_mib
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
cmake --build "$build" --target bench_surface >/dev/null
echo "n,threads,repeats,median_s,c2r_floor_s,ratio_to_floor,peak_rss_mib,model_mib"
for n in 512 1024 2048 4096 8192; do
  repeats=5; [ "$n" -ge 4096 ] && repeats=3
  for t in 1 2; do OMP_NUM_THREADS=$t "$build/bench_surface" "$n" "$repeats"; done
done
