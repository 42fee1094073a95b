#!/usr/bin/env bash
# indentmap mpi-indent (MPI builds; skipped, exit 77, elsewhere): the same result and the same
# field files to the byte on 1 and 3 ranks, a file surface read back, and clear errors.
#   cli_mpi.sh PATH_TO_INDENTMAP
set -uo pipefail
cli=$1
"$cli" --help | grep -q mpi-indent || { echo "built without MPI: skipped"; exit 77; }
mpiexec=$(command -v mpiexec || command -v mpirun) || { echo "no mpiexec: skipped"; exit 77; }
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_mpi_yield_when_idle=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }

# (at tol 1e-8, which the gap bar below was set for; the default is 1e-6)
for k in 1 3; do
  "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --n 64 --m 48 --approach 3 --tol 1e-8 --out "$work/out$k" --map 8 \
    > "$work/stdout$k" || fail "mpi-indent on $k ranks exited with $?"
  cut -d, -f1-5 "$work/stdout$k" > "$work/result$k"   # without the seconds
done
cmp -s "$work/result1" "$work/result3" || fail "1 and 3 ranks differ: $(cat "$work/result1" "$work/result3")"
for f in force gap force_map; do
  cmp -s "$work/out1/$f.npy" "$work/out3/$f.npy" || fail "$f.npy differs between 1 and 3 ranks"
done
contact=$(sed -n 2p "$work/result1" | cut -d, -f3)
[ "$contact" -gt 100 ] || fail "expected a contact of many patches, got '$contact'"
# the fields agree with the result: sum of forces = load (to the 6 digits 'surface --stats' prints; no
# detrending, which would take the mean out),
# no gap below zero beyond the tolerance
load=$(sed -n 2p "$work/result1" | cut -d, -f2)
mean=$("$cli" surface --stats "$work/out1/force.npy" --detrend none | awk '$1 == "mean" {print $2}')
awk -v m="$mean" -v l="$load" 'BEGIN { d = m * 64 * 48 / l - 1; exit !(d < 1e-5 && d > -1e-5) }' ||
  fail "force.npy sums to $mean x 3072, the load is $load"
# the 8 x 8 map: 8 x 6 blocks (a .npy file keeps no patch side), the same total force
"$cli" surface --stats "$work/out1/force_map.npy" --detrend none > "$work/map_stats"
grep -q "grid *8 x 6," "$work/map_stats" || fail "force_map.npy: $(head -1 "$work/map_stats")"
map_mean=$(awk '$1 == "mean" {print $2}' "$work/map_stats")
awk -v m="$map_mean" -v l="$load" 'BEGIN { d = m * 48 / l - 1; exit !(d < 1e-5 && d > -1e-5) }' ||
  fail "force_map.npy sums to $map_mean x 48, the load is $load"
lowest=$("$cli" surface --stats "$work/out1/gap.npy" --detrend none | awk '$1 == "height" {gsub(/[\[,]/, "", $3); print $3}')
awk -v g="$lowest" 'BEGIN { exit !(g > -1e-6) }' || fail "gap.npy goes down to $lowest"

# a hardness cap: the same result on 1 and 3 ranks, no force above H (force = pressure at delta 1)
for k in 1 3; do
  "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --n 64 --m 48 --approach 3 --hardness 0.12 --tol 1e-8 \
    --out "$work/cap$k" | cut -d, -f1-5 > "$work/cap_result$k" || fail "mpi-indent --hardness on $k ranks"
done
cmp -s "$work/cap_result1" "$work/cap_result3" || fail "--hardness: 1 and 3 ranks differ: $(cat "$work/cap_result"*)"
cmp -s "$work/cap_result1" "$work/result1" && fail "--hardness changed nothing: $(cat "$work/cap_result1")"
highest=$("$cli" surface --stats "$work/cap1/force.npy" --detrend none | awk '$1 == "height" {gsub(/[\],]/, "", $4); print $4}')
awk -v h="$highest" 'BEGIN { exit !(h <= 0.12 && h > 0.119) }' || fail "--hardness 0.12: the largest force is $highest"

# a surface from a file (the gap just written is a valid height field) on 2 ranks
"$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --surface "$work/out1/gap.npy" --punch sphere --radius 50 \
  --load 10 > "$work/stdout_file" || fail "mpi-indent --surface exited with $?"
[ "$(sed -n 2p "$work/stdout_file" | cut -d, -f2)" = 10 ] || fail "load control: $(cat "$work/stdout_file")"

# errors: a clear message and exit status 2 (bad input) or 1
"$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 64 > /dev/null 2> "$work/err1"
status=$?
[ $status -ne 0 ] && grep -q "give --approach W or --load N" "$work/err1" || fail "missing target: status $status, $(cat "$work/err1")"
"$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --surface "$work/missing.npy" --approach 1 > /dev/null 2> "$work/err2"
status=$?
[ $status -ne 0 ] && grep -q "missing.npy: cannot open" "$work/err2" || fail "missing file: status $status, $(cat "$work/err2")"
echo "cli_mpi: ok"
