#!/usr/bin/env bash
# The quality presets on the paper's configuration (issue 7): 512 x 512, H 0.8, h'rms 0.08,
# lambda_s 4, lambda_r 512, seed 1; cone 80 deg; 25 approaches 1.26 .. 31.5 (displacement control).
# Each preset's history against the same history at tol 1e-11: the largest relative error over the
# steps of n_p and of N; wall and CPU time of the whole `indent` run (planning included), medians of
# REPEATS (the reference runs once).
#   BUILD=build-trade THREADS=2 REPEATS=3 bench/run_presets.sh > presets.csv
# Prints CSV: preset,tol,threads,repeats,wall_median_s,wall_min_s,wall_max_s,cpu_median_s,iterations,
#             max_rel_error_np,max_rel_error_N,max_residual,worst_np_step,reference_np_there,
#             load_average_before
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
threads=${THREADS:-2}
repeats=${REPEATS:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=$threads OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
cli=$build/indentmap

"$cli" surface --n 512 --hurst 0.8 --slope 0.08 --lambda-s 4 --lambda-r 512 --seed 1 \
  --out "$work/s.npy" >/dev/null

# run NAME TOL-OPTIONS...: one history into $work/NAME; prints its wall and CPU (user + system)
# seconds.
run() {
  local name=$1 TIMEFORMAT='%R %U %S'
  shift
  { time "$cli" indent "$work/s.npy" --approach 1.26:31.5:25 "$@" --out "$work/$name" >/dev/null 2>&1; } 2>&1 |
    awk '{printf "%.3f %.3f\n", $1, $2 + $3}'
}

# median of column COLUMN of stdin (and, with a second argument, its min and max too)
median() { awk -v c="$1" '{print $c}' | sort -g | awk -v all="${2:-}" '{v[NR] = $1}
  END {m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
       if (all) printf "%.3f,%.3f,%.3f", m, v[1], v[NR]; else printf "%.3f", m}'; }

# compare A B: largest relative errors of n_p and N of history A against history B, the iterations
# summed over A's steps, A's largest residual, and the step of the largest n_p error with B's n_p there.
compare() {
  awk -F, 'NR == FNR { if (FNR > 1) { np[$1] = $5; n[$1] = $3 } next }
           FNR > 1 { e = np[$1] > 0 ? ($5 - np[$1]) / np[$1] : 0; if (e < 0) e = -e;
                     if (e > enp) { enp = e; worst = $1; at = np[$1] }
                     e = ($3 - n[$1]) / n[$1]; if (e < 0) e = -e; if (e > en) en = e;
                     it += $9; if ($10 > res) res = $10 }
           END { printf "%d,%.3e,%.3e,%.3e,%d,%d", it, enp, en, res, worst, at }' "$2/history.csv" "$1/history.csv"
}

load=$(cut -d' ' -f1 /proc/loadavg)
ref_time=$(run reference --tol 1e-11)
echo "preset,tol,threads,repeats,wall_median_s,wall_min_s,wall_max_s,cpu_median_s,iterations,max_rel_error_np,max_rel_error_N,max_residual,worst_np_step,reference_np_there,load_average_before"
echo "reference,1e-11,$threads,1,$(echo "$ref_time" | median 1 all),$(echo "$ref_time" | median 2),$(compare "$work/reference" "$work/reference"),$load"
for preset in draft:1e-5 standard:1e-6 publication:1e-9 ${EXTRA_TOLS:-}; do
  name=${preset%%:*} tol=${preset#*:}
  load=$(cut -d' ' -f1 /proc/loadavg)
  option=(--quality "$name")
  [ "$name" = tol ] && option=(--tol "$tol") && name=tol$tol
  times=$(for k in $(seq "$repeats"); do run "$name" "${option[@]}"; done)
  echo "$name,$tol,$threads,$repeats,$(echo "$times" | median 1 all),$(echo "$times" | median 2),$(compare "$work/$name" "$work/reference"),$load"
done
