#!/usr/bin/env bash
# Threads for library users (issue 33): a C program linking libindentmap (bench_library_threads) and a
# Python script importing indentmap (bench_library_threads.py), each doing a cold 80 deg cone solve and a
# periodic flat-contact solve of a rough n x n surface (default 512), at 1 and 2 OpenMP threads, on a quiet
# machine and beside one competing busy process (`while :; do :; done`, pinned nowhere). No CLI and no
# re-execution: what a program or a notebook gets. Runs are alternated (1 thread, 2 threads, C then Python,
# each repeat) and each cell is the median of the repeats. Prints the machine, the load average before and
# after, then one CSV line per language and solve:
#
#   language,solve,repeats,quiet_1t_s,quiet_2t_s,cpu_ratio,busy_1t_s,busy_2t_s,bar_s,busy_2t_over_bar,results
#
# cpu_ratio: the median over quiet repeats of the 2-thread run's CPU time over the 1-thread run's (the same
# work, so above 1 only by what slows a thread when two run: bench/run_threads.sh). bar_s: the better of
# busy_1t_s and quiet_2t_s x cpu_ratio; the issue's goal is busy_2t_over_bar <= 1.3. results: 'identical'
# when every run of that solve gave the same load (the periodic cell: approach) to the last bit and the
# same contact count, whatever the threads and load; else the distinct values seen.
#
# usage: BUILD=dir bench/run_library_threads.sh [--repeats R] [--n N]   (defaults 5, 512; BUILD default build)
# Builds what it needs. The library's choices are the user's: OMP_WAIT_POLICY, GOMP_SPINCOUNT and
# OMP_NUM_THREADS are passed through as set (OMP_NUM_THREADS then pins the 2-thread runs' count too).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
repeats=5 n=512
while [ $# -gt 0 ]; do
  case $1 in
    --repeats) repeats=$2; shift 2 ;;
    --n) n=$2; shift 2 ;;
    *) echo "usage: BUILD=dir bench/run_library_threads.sh [--repeats R] [--n N]" >&2; exit 2 ;;
  esac
done
cmake --build "$build" --target bench_library_threads indentmap_python indentmap_python_modules >/dev/null
. bench/stats.sh
work=$(mktemp -d)
busy=""
stop_busy() { if [ -n "$busy" ]; then kill "$busy" 2>/dev/null || true; wait "$busy" 2>/dev/null || true; busy=""; fi; }
trap 'stop_busy; rm -rf "$work"' EXIT

# Python has no thread-count call: 2 threads are OpenMP's default on a 2-core machine, OMP_NUM_THREADS=2
# elsewhere (which pins the count).
python_threads_env() {
  if [ "$1" = 1 ] || [ "$(nproc)" != 2 ]; then echo "OMP_NUM_THREADS=$1"
  elif [ -n "${OMP_NUM_THREADS:-}" ]; then echo "OMP_NUM_THREADS=$OMP_NUM_THREADS"
  else echo "-u OMP_NUM_THREADS"; fi
}

run_c() { "$build/bench_library_threads" --n "$n" --threads "$1"; }
run_python() {
  env $(python_threads_env "$1") PYTHONPATH="$build/python" /usr/bin/python3 bench/bench_library_threads.py "$n" |
    sed 's/^\([a-z]*,[0-9]*\),[^,]*,/\1,'"$1"',/'
}

# Appends "wall cpu result contact" to $work/LANGUAGE.CONDITION.SOLVE.THREADS for each solve line.
record() { # language condition threads
  awk -F, -v d="$work" -v l="$1" -v c="$2" -v t="$3" \
    '{print $4, $5, $7, $8 >> (d "/" l "." c "." $1 "." t)}'
}

measure() { # condition
  local r t
  for r in $(seq "$repeats"); do
    for t in 1 2; do
      run_c "$t" | record c "$1" "$t"
      run_python "$t" | record python "$1" "$t"
    done
    echo "# $1 repeat $r done, load $(cut -d' ' -f1-4 /proc/loadavg)"
  done
}

column_median() { cut -d' ' -f"$2" "$1" | median; }

summarise() { # language solve
  local q1="$work/$1.quiet.$2.1" q2="$work/$1.quiet.$2.2" b1="$work/$1.busy.$2.1" b2="$work/$1.busy.$2.2"
  local quiet1 quiet2 cpu busy1 busy2 bar results
  quiet1=$(column_median "$q1" 1); quiet2=$(column_median "$q2" 1)
  busy1=$(column_median "$b1" 1); busy2=$(column_median "$b2" 1)
  cpu=$(paste -d' ' "$q1" "$q2" | awk '{print $6 / $2}' | median)
  bar=$(awk -v a="$busy1" -v b="$quiet2" -v c="$cpu" 'BEGIN {x = b * c; printf "%.4f", a < x ? a : x}')
  results=$(cat "$q1" "$q2" "$b1" "$b2" | cut -d' ' -f3,4 | sort -u)
  [ "$(wc -l <<<"$results")" = 1 ] && results=identical || results=$(tr '\n' ';' <<<"$results")
  echo "$1,$2,$repeats,$quiet1,$quiet2,$(printf %.2f "$cpu"),$busy1,$busy2,$bar,$(ratio "$busy2" "$bar"),$results"
}

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; $(date -u +%FT%TZ); commit $(git rev-parse --short HEAD 2>/dev/null || echo '?')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-unset} GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-unset} OMP_NUM_THREADS=${OMP_NUM_THREADS:-unset}; n=$n"
measure quiet
(while :; do :; done) &
busy=$!
measure busy
stop_busy
echo "language,solve,repeats,quiet_1t_s,quiet_2t_s,cpu_ratio,busy_1t_s,busy_2t_s,bar_s,busy_2t_over_bar,results"
for language in c python; do
  for solve in cone periodic; do summarise "$language" "$solve"; done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
