#!/usr/bin/env bash
# Amdahl from a CPU profile (docs/benchmarks.md, "Two threads against one"): the total CPU time of a
# `perf record -F HZ` profile and its critical path, the sum over 50 ms bins of the busiest thread's
# samples. A part that runs on one thread adds its whole time, a balanced part half its CPU time, so on
# a quiet machine the wall time of a 2-thread run is about its critical path, whatever the load was.
#
# usage: OMP_NUM_THREADS=2 perf record -F 999 -o run.data -- COMMAND...; bench/critical_path.sh run.data [HZ]
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: bench/critical_path.sh PERF.DATA [HZ (default 999)]" >&2; exit 2; }
perf script -i "$1" -F tid,time 2>/dev/null | awk -v hz="${2:-999}" '
  { t = $2; sub(":", "", t); if (first == "") first = t
    bin = int((t - first) / 0.05); samples[bin " " $1]++; threads[$1] = 1; if (bin > last) last = bin; total++ }
  END { path = 0
        for (b = 0; b <= last; b++) { most = 0; for (x in threads) if (samples[b " " x] > most) most = samples[b " " x]; path += most }
        printf "total CPU %.2f s, critical path %.2f s\n", total / hz, path / hz }'
