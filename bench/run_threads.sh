#!/usr/bin/env bash
# Two threads against one (issue 15): wall and CPU time of the paper's fig4 scene and of one cold solve
# (bench_cold) at 1 and 2 OpenMP threads, median of repeats, 1- and 2-thread runs alternated so that a
# change of load hits both alike. Prints the machine, the load average before and after, and a table:
#
#   what,threads,repeats,median_wall_s,min_wall_s,median_cpu_s,median_ratio_1_over_2,min_ratio_1_over_2,
#   paired_ratio_median (the median over repeats of one repeat's 1-thread wall / its 2-thread wall),
#   cpu_2_over_1_median (a repeat's 2-thread CPU time / its 1-thread CPU time: the same work, so above 1
#   only by what makes each thread slower when two run: a host that puts the two virtual CPUs on one
#   physical core's two hardware threads, a neighbour, shared caches, or our own spinning),
#   quiet_estimate_median (paired ratio x CPU ratio, per repeat: the ratio had the second thread cost
#   no extra CPU time, i.e. the part of the speed-up the program decides; it counts our own extra CPU
#   time, e.g. spin-waiting, as the machine's, which raises it, and the host running the two threads at
#   different speeds as ours, which lowers it: build/bench_cores' register kernel reads 1.89-1.99),
#   uncontended (the median paired ratio, and how many, of the repeats whose 2-thread run took at most
#   1.05x its 1-thread run's CPU time: those most likely had two cores to themselves; '-' if none)
#
# On the project's 2-core VM bench_cores (a register-only kernel with no serial part) gains 1.0-2.0x from
# two threads within one minute, and a 512^2 solve's paired ratio is 1.86-1.99 / CPU ratio in every repeat
# (0.85x at a CPU ratio of 2.27, 2.12x at 0.94): only the estimate and the uncontended repeats say what
# the program does on a quiet machine. Each repeat also prints a comment line with its times.
# fft_pair_floor_N: the median wall time of the FFT pair each solve needs (bench_cold's floor) at 1 and 2
# threads and their ratio: what FFTW's own threads gain on that transform. The minimum is printed beside
# the median because a shared virtual machine's neighbours only ever add time: on the project's 2-core
# VM the same run varied by +-15% within minutes.
# usage: bench/run_threads.sh [--repeats R] [--only fig4|solver] [--sizes "512 1024"] [--no-wisdom]
# fig4 keeps FFTW wisdom in a temporary cache, as the CLI does in the user's: one untimed run per thread
# count fills it first (--no-wisdom: none, FFTW_ESTIMATE plans). bench_cold plans with FFTW_ESTIMATE.
# (BUILD=DIR picks the build folder, default build.) Threads spin briefly, then sleep (GOMP_SPINCOUNT=3000
# unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set), as the CLI's do by default.
# Take the timings on a quiet machine: the load average is printed so that a loaded run shows.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${BUILD:-build}
repeats=3 only="" sizes="512 1024" wisdom=""
while [ $# -gt 0 ]; do
  case $1 in
    --repeats) repeats=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --sizes) sizes=$2; shift 2 ;;
    --no-wisdom) wisdom=--no-wisdom; shift ;;
    *) echo "usage: bench/run_threads.sh [--repeats R] [--only fig4|solver] [--sizes \"512 1024\"] [--no-wisdom]" >&2; exit 2 ;;
  esac
done
cmake --build "$build" --target indentmap_cli bench_cold >/dev/null
if [ -z "${OMP_WAIT_POLICY:-}" ]; then export GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-3000}; fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

. bench/stats.sh

# One fig4 run in a fresh folder: "wall cpu" (CPU = user + system of the process and its threads).
fig4_once() {
  local dir="$work/fig4_$1"
  mkdir -p "$dir"
  (cd "$dir" && OMP_NUM_THREADS=$1 XDG_CACHE_HOME="$work/cache" /usr/bin/time -f "%e %U %S" -o time.txt \
    "$root/$build/indentmap" run "$root/scenes/fig4.ini" --quiet $wisdom >/dev/null)
  awk '{printf "%s %.2f\n", $1, $2 + $3}' "$dir/time.txt"
  rm -rf "$dir"
}

# One bench_cold process (it repeats the solve itself): "wall cpu" of its median solve; the wall time of
# the FFT pair it needs (its floor) is kept in $work/pair_N.T.
solver_once() {
  local out
  out=$("$build/bench_cold" --n "$1" --threads "$2" --repeats 1)
  sed -n 's/.*FFT pair of the padded window.*: wall \([0-9.]*\) ms.*/\1/p' <<<"$out" >>"$work/pair_$1.$2"
  sed -n 's/.*wall \([0-9.]*\) s, CPU \([0-9.]*\) s.*/\1 \2/p' <<<"$out"
}

run_pair() { # what, command (called as: command THREADS)
  local what=$1 cmd=$2 t r
  for r in $(seq "$repeats"); do
    for t in 1 2; do $cmd "$t" >>"$work/$what.$t"; done
    echo "# $what repeat $r: 1 thread $(tail -1 "$work/$what.1"), 2 threads $(tail -1 "$work/$what.2") (wall cpu s)"
  done
  local w1 c1 w2 c2 m1 m2
  w1=$(cut -d' ' -f1 "$work/$what.1" | median); c1=$(cut -d' ' -f2 "$work/$what.1" | median)
  w2=$(cut -d' ' -f1 "$work/$what.2" | median); c2=$(cut -d' ' -f2 "$work/$what.2" | median)
  m1=$(cut -d' ' -f1 "$work/$what.1" | sort -g | head -1); m2=$(cut -d' ' -f1 "$work/$what.2" | sort -g | head -1)
  # per repeat (its 1-thread run and the 2-thread run right after it saw about the same neighbours):
  # "wall ratio, CPU ratio, their product"
  paste -d' ' "$work/$what.1" "$work/$what.2" | awk '{print $1 / $3, $4 / $2, $1 / $3 * $4 / $2}' >"$work/$what.r"
  local paired inflation estimate quiet uncontended=-
  paired=$(cut -d' ' -f1 "$work/$what.r" | median)
  inflation=$(cut -d' ' -f2 "$work/$what.r" | median)
  estimate=$(cut -d' ' -f3 "$work/$what.r" | median)
  quiet=$(awk '$2 <= 1.05 {print $1}' "$work/$what.r")
  [ -n "$quiet" ] && uncontended="$(printf %.2f "$(median <<<"$quiet")") ($(wc -l <<<"$quiet"))"
  echo "$what,1,$repeats,$w1,$m1,$c1,-,-,-,-,-,-"
  echo "$what,2,$repeats,$w2,$m2,$c2,$(ratio "$w1" "$w2"),$(ratio "$m1" "$m2"),$(printf %.2f "$paired"),$(printf %.2f "$inflation"),$(printf %.2f "$estimate"),$uncontended"
}

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; $(date -u +%FT%TZ); commit $(git rev-parse --short HEAD 2>/dev/null || echo '?')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg); OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-unset} GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-unset}"
echo "what,threads,repeats,median_wall_s,min_wall_s,median_cpu_s,median_ratio_1_over_2,min_ratio_1_over_2,paired_ratio_median,cpu_2_over_1_median,quiet_estimate_median,uncontended"
if [ "$only" != solver ]; then
  fig4_once 1 >/dev/null && fig4_once 2 >/dev/null # fills the wisdom cache
  run_pair fig4 fig4_once
fi
if [ "$only" != fig4 ]; then
  for n in $sizes; do
    eval "solver_$n() { solver_once $n \"\$1\"; }"
    run_pair "solver_$n" "solver_$n"
    p1=$(median <"$work/pair_$n.1"); p2=$(median <"$work/pair_$n.2")
    echo "fft_pair_floor_$n,1-2,$repeats,$p1 ms,$p2 ms,-,$(ratio "$p1" "$p2"),-,-,-,-,-"
  done
fi
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
