#!/usr/bin/env bash
# Per-iteration cost against the FFT floor (issue 33; bench/bench_floor.c): every solve kind (cold rough
# cone; periodic cell under mean pressure and under mean gap; one step of the paper's history) at each
# size, 1 and 2 threads alternated within one process per size, medians of the repeats. Prints the machine
# and the load average before and after each size, then bench_floor's lines, and at the end the exponent
# of a least-squares fit CPU time ~ n^b per kind and thread count over the sizes (the floor grows as
# n^2 log n: b = 2.1-2.2 over 512-2048).
# usage: bench/run_floor.sh [--repeats R] [--sizes "512 1024 2048"]   (BUILD=DIR, default build)
set -euo pipefail
repeats=3
sizes="512 1024 2048"
while [ $# -gt 0 ]; do
    case "$1" in
    --repeats) repeats="$2"; shift 2 ;;
    --sizes) sizes="$2"; shift 2 ;;
    *) echo "usage: $0 [--repeats R] [--sizes \"512 1024 2048\"]" >&2; exit 2 ;;
    esac
done
build="${BUILD:-build}"
[ -x "$build/bench_floor" ] || { echo "$0: $build/bench_floor not built (cmake --build $build --target bench_floor)" >&2; exit 1; }
export IM_FFTW_WISDOM= # FFTW_ESTIMATE plans, no wisdom file touched
# threads spin briefly, then sleep, as the CLI's do (bench/run_threads.sh): a spinning FFTW thread on a
# shared core counts the neighbour's time as ours
[ -n "${OMP_WAIT_POLICY:-}" ] || export GOMP_SPINCOUNT="${GOMP_SPINCOUNT:-3000}"
echo "# $(nproc) CPUs, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for n in $sizes; do
    echo "# n $n: load before $(cut -d' ' -f1-3 /proc/loadavg)"
    "$build/bench_floor" --n "$n" --repeats "$repeats" | tee -a "$out"
    echo "# n $n: load after $(cut -d' ' -f1-3 /proc/loadavg)"
done
# the fit: log(CPU time) against log(n) per kind and thread count
awk '{
    kind = $1; n = $3; threads = $5 + 0
    for (i = 1; i <= NF; ++i) {
        if ($i == "wall") wall = $(i + 1)
        if ($i == "CPU") cpu = $(i + 1)
    }
    key = kind " threads " threads
    x = log(n); y = log(cpu)
    sx[key] += x; sy[key] += y; sxx[key] += x * x; sxy[key] += x * y; count[key]++
} END {
    for (key in count)
        if (count[key] > 1)
            printf "# fitted exponent %s: time ~ n^%.2f over %d sizes\n", key,
                (count[key] * sxy[key] - sx[key] * sy[key]) / (count[key] * sxx[key] - sx[key] * sx[key]), count[key]
}' "$out" | sort
