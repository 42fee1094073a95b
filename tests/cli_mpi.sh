#!/usr/bin/env bash
# indentmap mpi-indent (MPI builds; skipped, exit 77, elsewhere): the same result and the same
# field files to the byte on 1 and 3 ranks, a file surface read back, and clear errors; ranks
# started with different commands, folders or scenes, reading other bytes from a file the scene
# names or from mpi-indent's --surface, or an error on one rank only, stop every rank with one
# message (mpi-indent and run under mpirun), never a hang or MPI's own error.
#   cli_mpi.sh PATH_TO_INDENTMAP
set -uo pipefail
cli=$1
"$cli" --help | grep -q mpi-indent || { echo "built without MPI: skipped"; exit 77; }
mpiexec=$(command -v mpiexec || command -v mpirun) || { echo "no mpiexec: skipped"; exit 77; }
source "$(dirname "$0")/mpi/open_mpi_env.sh"
export OMP_NUM_THREADS=1
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

# a flat punch (refused before the MPI parity work, though the solver takes it): the same result on 1 and
# 3 ranks, its contact within the punch's radius 12 (at most the 441 patches whose centres lie within 12 of the axis)
for k in 1 3; do
  "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --n 64 --m 48 --punch flat --radius 12 --approach 1 --tol 1e-8 \
    2> "$work/flat$k.err" | cut -d, -f1-5 > "$work/flat_result$k" || fail "--punch flat on $k ranks: $(cat "$work/flat$k.err")"
done
cmp -s "$work/flat_result1" "$work/flat_result3" || fail "--punch flat: 1 and 3 ranks differ: $(cat "$work/flat_result"*)"
flat_contact=$(sed -n 2p "$work/flat_result1" | cut -d, -f3)
[ "${flat_contact:-0}" -gt 100 ] && [ "$flat_contact" -le 441 ] || fail "--punch flat: $(cat "$work/flat_result1")"

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
# a surface whose sidecar states a spacing other than 1, or the order [x, y], was solved as if in units of
# delta = 1, rows along y: another problem, without a word (N 7.38 on 83 patches for indent's 3.69 on 7)
"$cli" surface --n 64 --m 48 --delta 2.5 --unit nm --out "$work/nm.npy" > /dev/null || fail "surface in nm"
"$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --surface "$work/nm.npy" --approach 1 > /dev/null 2> "$work/err3"
status=$?
[ $status -eq 2 ] && grep -q "surface .*nm.npy: its sidecar .*nm.npy.json states delta = 2.5 nm, but mpi-indent reads heights in units of delta = 1" \
  "$work/err3" || fail "a sidecar's spacing: status $status, $(cat "$work/err3")"
"$cli" surface --n 16 --out "$work/xy.npy" > /dev/null && printf '{"delta": 1, "order": "xy"}\n' > "$work/xy.npy.json"
"$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --surface "$work/xy.npy" --approach 0.3 > /dev/null 2> "$work/err4"
status=$?
[ $status -eq 2 ] && grep -q "states the order xy (indexed \[x, y\]), but mpi-indent reads rows along y" "$work/err4" \
  || fail "a sidecar's order xy: status $status, $(cat "$work/err4")"
# A grid smaller than the rank count: a 3 x 3 surface (6 padded rows) on 7 ranks, some of them with
# no rows, gives the one-rank result; a side not above lambda_s = 4 is refused naming --n and --m.
"$cli" surface --n 3 --lambda-s 2 --out "$work/s3.npy" > /dev/null || fail "surface --n 3"
for k in 1 7; do
  timeout 120 "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --surface "$work/s3.npy" --alpha 60 --approach 0.3 \
    --out "$work/fields$k" 2> "$work/small$k.err" | cut -d, -f1-5 > "$work/small$k" || fail "3 x 3 on $k ranks: $(cat "$work/small$k.err")"
done
cmp -s "$work/small1" "$work/small7" && cmp -s "$work/fields1/force.npy" "$work/fields7/force.npy" ||
  fail "a 3 x 3 grid: 1 and 7 ranks differ: $(cat "$work/small1" "$work/small7")"

# refused NAME EXIT PATTERN MPIEXEC_ARGUMENTS...: mpiexec ends within 60 s (a hang is a failure)
# with exit status EXIT and one message from indentmap, matching PATTERN.
refused() {
  local name=$1 expected=$2 pattern=$3
  shift 3
  timeout 300 "$mpiexec" --oversubscribe "$@" > /dev/null 2> "$work/$name.err"
  local status=$?
  [ $status -eq "$expected" ] || fail "$name: exit $status, expected $expected: $(cat "$work/$name.err")"
  grep -q -- "$pattern" "$work/$name.err" || fail "$name: expected '$pattern': $(cat "$work/$name.err")"
  [ "$(grep -c '^indentmap:' "$work/$name.err")" = 1 ] || fail "$name: not one message: $(cat "$work/$name.err")"
}
refused tiny_grid 2 "mpi-indent: --n 2 --m 2: the shorter side .* must exceed lambda_s = 4: expected --n and --m > 4" \
  -n 3 "$cli" mpi-indent --n 2 --approach 1
# --n alone is a square grid, as indent's and surface's (it was --n x 512)
"$mpiexec" -n 1 --oversubscribe "$cli" mpi-indent --n 40 --approach 1 --out "$work/square" > /dev/null 2> "$work/square.err" ||
  fail "--n 40: $(cat "$work/square.err")"
head -c 128 "$work/square/force.npy" | grep -q "'shape': (40, 40)" || fail "--n 40: $(head -c 128 "$work/square/force.npy")"
# an output that is a symbolic link is written through, as every other writer's (io.h, im_atomic_open): the link
# stays and its (dangling) target gets the rows of both ranks
mkdir -p "$work/linked" "$work/targets" && ln -s ../targets/force.npy "$work/linked/force.npy"
"$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 40 --approach 1 --out "$work/linked" > /dev/null 2> "$work/linked.err" ||
  fail "--out through a link: $(cat "$work/linked.err")"
[ -L "$work/linked/force.npy" ] && cmp -s "$work/targets/force.npy" "$work/square/force.npy" ||
  fail "--out through a link: $(ls -l "$work/linked" "$work/targets")"

# --periodic: indent --periodic's history of a rigid flat on the cell (mean pressures, mean gaps, and mean
# pressures and mean gaps under a cap with plastic memory, unloading at step 3; a yielding cell's mean gap is
# searched over the approach, refused by name before that search was shared): the same iterations and the same values
# to the tolerance (residuals to 1e-3 of theirs; seconds and convolutions, which the MPI solver spends
# otherwise, aside), and the same bytes on 1, 2 and 3 ranks but for the seconds.
"$cli" surface --n 64 --seed 3 --out "$work/p.npy" > /dev/null || fail "surface for --periodic"
source "$(dirname "$0")/mpi/history_compare.sh"
same_history() { history_differences "$1" "$2" 1e-8; } # same_history SERIAL MPI: 0 when they agree
# Under the sanitizers (CMake sets IM_SANITIZED=1 in that build, where each mpirun costs seconds of Open MPI's start
# and LeakSanitizer's exit checks) the periodic histories run on 1 and 3 ranks, not 2, and run.json, history.csv
# and the figure are read from the 3-rank run: the 3-rank run takes the 2-rank run's C paths (FFTW-MPI's blocks of
# ceil(64 / ranks) rows: 32 + 32 and 22 + 22 + 20, every rank holding rows and spectrum columns, the same
# exchanges and reductions): rows split unevenly on 3, the spectrum columns on 2 (17 + 16), whose larger column
# slab the 2-rank non-periodic cases size there. The plain pass compares all three, files from 2 ranks.
periodic_ranks="1 2 3" files_rank=2
[ "${IM_SANITIZED:-0}" = 1 ] && periodic_ranks="1 3" files_rank=3
periodic_case() { # periodic_case NAME ARGUMENTS...: indent --periodic against mpi-indent on $periodic_ranks ranks
  local name=$1
  shift
  "$cli" indent "$work/p.npy" --periodic --tol 1e-8 "$@" --out "$work/ser_$name" > /dev/null 2>&1 ||
    fail "indent --periodic $*"
  for k in $periodic_ranks; do
    timeout 300 "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --periodic --surface "$work/p.npy" --tol 1e-8 "$@" \
      --out "$work/mpi_${name}_$k" > "$work/mpi_$name$k.csv" 2> "$work/mpi_$name.err" ||
      fail "mpi-indent --periodic $* on $k ranks (exit $?, 124: timed out): $(cat "$work/mpi_$name.err")"
    cut -d, -f1-10,12- "$work/mpi_$name$k.csv" > "$work/mpi_$name$k.cut"
  done
  same_history "$work/ser_$name/history.csv" "$work/mpi_${name}1.csv" > "$work/diff_$name" ||
    fail "mpi-indent --periodic $* is not indent's history: $(head -5 "$work/diff_$name")"
  for k in ${periodic_ranks#1 }; do
    cmp -s "$work/mpi_${name}1.cut" "$work/mpi_$name$k.cut" || fail "mpi-indent --periodic $*: 1 and $k ranks differ"
  done
  local files="$work/mpi_${name}_$files_rank"
  cmp -s "$work/mpi_$name$files_rank.csv" "$files/history.csv" || fail "--periodic $*: history.csv is not stdout"
  grep -q '"periodic": true' "$files/run.json" || fail "--periodic $*: run.json: $(cat "$files/run.json")"
}
periodic_case pressure --pressure 0.01:0.05:3
periodic_case gap --mean-gap 0.3,0.1,0.05
periodic_case cap --pressure 0.02,0.05,0.03,0.06 --hardness 0.1
periodic_case gap_cap --mean-gap 0.3,0.1,0.05,0.2 --hardness 0.1
column_of() { head -1 "$2" | tr , '\n' | grep -nx "$1" | cut -d: -f1; }
yielding=$(cut -d, -f"$(column_of yielding_patches "$work/ser_gap_cap/history.csv")" "$work/ser_gap_cap/history.csv" |
  sed 1d | tr '\n' ' ')
awk -v y="$yielding" 'BEGIN { n = split(y, v, " "); exit !(n == 4 && v[2] > 0 && v[3] > v[2] && v[4] == 0) }' ||
  fail "--mean-gap with --hardness 0.1: the cap should bind at mean gaps 0.1 and 0.05, not on unloading: $yielding"
# adhesion (indent's Maugis-Dugdale passes over the ranks; refused before): approach, deeper, retraction to a
# pulled cell, every step under tension, the zone's share exchanged across the ranks' rows
periodic_case adhesion --mean-gap 0.3,0.15,0.6,0.9 --adhesion-work 0.002 --adhesion-range 0.2
tensile=$(cut -d, -f"$(column_of adhesive_patches "$work/ser_adhesion/history.csv")" "$work/ser_adhesion/history.csv" |
  sed 1d | tr '\n' ' ')
awk -v t="$tensile" 'BEGIN { n = split(t, v, " "); exit !(n == 4 && v[1] > 0 && v[2] > v[1] && v[3] > 0 && v[4] > 0) }' ||
  fail "--adhesion-work 0.002: every step should have patches under tension: $tensile"
# the most tensile load to 1e-8, and the pull-off said alike (null: the last retracting step pulls hardest)
pull_off_of() { grep "\"$2\"" "$1" | head -1 | sed 's/.*: //; s/,$//'; }
serial_pull=$(pull_off_of "$work/ser_adhesion/run.json" most_tensile_load)
mpi_pull=$(pull_off_of "$work/mpi_adhesion_$files_rank/run.json" most_tensile_load)
awk -v a="$serial_pull" -v b="$mpi_pull" 'BEGIN { d = a - b; exit !(a > 0 && d < 1e-8 * a && -d < 1e-8 * a) }' ||
  fail "run.json's adhesion most tensile load: indent's '$serial_pull', mpi-indent's '$mpi_pull'"
[ "$(pull_off_of "$work/ser_adhesion/run.json" pull_off_force)" = "$(pull_off_of "$work/mpi_adhesion_$files_rank/run.json" pull_off_force)" ] ||
  fail "run.json's adhesion pull-off differs between indent and mpi-indent"
grep -q '"k_fit"' "$work/mpi_adhesion_$files_rank/run.json" && fail "an adhesive cell's run.json has a k fit (eq. (2) is repulsive)"
[ -s "$work/mpi_adhesion_$files_rank/force_distance.png" ] || fail "mpi-indent --adhesion-work: no force_distance.png"
refused adhesion_load 2 "mpi-indent: --adhesion-work takes --periodic --mean-gap LIST" \
  -n 2 "$cli" mpi-indent --periodic --n 64 --pressure 0.01 --adhesion-work 0.004 --adhesion-range 0.1
refused adhesion_cap 2 "mpi-indent: --periodic --adhesion-work with --hardness: a cell's adhesion with plasticity is not available over ranks" \
  -n 2 "$cli" mpi-indent --periodic --n 64 --mean-gap 0.1 --hardness 0.1 --adhesion-work 0.004 --adhesion-range 0.1
refused adhesion_range 2 "mpi-indent: --adhesion-work and --adhesion-range go together" \
  -n 2 "$cli" mpi-indent --periodic --n 64 --mean-gap 0.1 --adhesion-work 0.004
# a mean gap <= 0 is refused before any step is solved, as indent's (redteam T3: step 1 was solved first)
refused mean_gap_zero 2 "--mean-gap '0.4,0': step 2 is 0: expected mean gaps > 0" \
  -n 2 "$cli" mpi-indent --periodic --n 64 --mean-gap 0.4,0 --out "$work/mean_gap_zero"
[ ! -e "$work/mean_gap_zero/history.csv" ] || fail "--mean-gap 0.4,0: a step was solved before the refusal"
k_of() { grep -A1 '"k_fit"' "$1" | awk '$1 == "\"k\":" { sub(/,$/, "", $2); print $2 }'; }
serial_k=$(k_of "$work/ser_pressure/run.json") mpi_k=$(k_of "$work/mpi_pressure_$files_rank/run.json")
awk -v a="$serial_k" -v b="$mpi_k" 'BEGIN { d = a - b; exit !(a > 1 && d < 1e-9 * a && -d < 1e-9 * a) }' ||
  fail "k of eq. (2): indent's '$serial_k', mpi-indent's '$mpi_k'"
# what --periodic does not take
refused periodic_approach 2 "mpi-indent --periodic takes mean pressures (--pressure LIST) or mean gaps (--mean-gap LIST), not --approach or --load" \
  -n 2 "$cli" mpi-indent --periodic --n 64 --approach 1
refused periodic_punch 2 "mpi-indent --periodic presses a rigid flat on the whole cell: --punch, --alpha, --radius and --profile are the half-space's" \
  -n 2 "$cli" mpi-indent --periodic --n 64 --pressure 0.01 --alpha 70
refused periodic_targets 2 "mpi-indent --periodic: give --pressure LIST or --mean-gap LIST" -n 2 "$cli" mpi-indent --periodic --n 64
# the controls exclude one another, as in indent (the last one given was taken silently)
refused two_controls 2 "mpi-indent: give one of --approach, --load, --pressure and --mean-gap, once" \
  -n 1 "$cli" mpi-indent --n 64 --approach 1 --load 2
refused two_cell_controls 2 "mpi-indent: give one of --approach, --load, --pressure and --mean-gap, once" \
  -n 1 "$cli" mpi-indent --periodic --n 64 --pressure 0.01 --mean-gap 0.3
refused pressure_alone 2 "mpi-indent: --pressure (over a periodic cell) needs --periodic" -n 2 "$cli" mpi-indent --n 64 --pressure 0.01
refused periodic_list 2 "--pressure 'x': 'x' is not a number >= 0" -n 2 "$cli" mpi-indent --periodic --n 64 --pressure x
refused periodic_capacity 2 "step 1 of 1 (--pressure 0.2): load 819.2: a periodic cell at hardness 0.1 carries less than H_p A0 = 409.6" \
  -n 2 "$cli" mpi-indent --periodic --n 64 --m 64 --pressure 0.2 --hardness 0.1

# Ranks given different commands (MPMD launches, A : B) stop together with rank 0's message.
start="the MPI ranks were not started alike"
same="start every rank with the same command in the same folder"
cd "$work" || fail "cd $work"
refused out 2 "$start: rank 1 differs from rank 0 (rank 1's argument 7 is 'o2' (after --out), rank 0's 'o1'): $same" \
  -n 1 "$cli" mpi-indent --n 64 --approach 5 --out o1 : -n 1 "$cli" mpi-indent --n 64 --approach 5 --out o2
[ ! -e o1 ] && [ ! -e o2 ] || fail "different --out: a folder was made"
# Under the sanitizers (IM_SANITIZED=1) grid and control are left to the plain pass, their C paths run by out and
# scenes there (src/mpi/inputs.c): grid's is out's (mpi-indent on 2 ranks, one differing rank, describe()'s
# "(after --OPTION)" branch); control's is scenes' (describe()'s plain branch past the first word, where the
# strncmp against the word before fails), its launch on 3 ranks commands'.
if [ "${IM_SANITIZED:-0}" != 1 ]; then
  refused grid 2 "$start: rank 1 differs from rank 0 (rank 1's argument 3 is '32' (after --n), rank 0's '64')" \
    -n 1 "$cli" mpi-indent --n 64 --approach 5 : -n 1 "$cli" mpi-indent --n 32 --approach 5
  refused control 2 "$start: rank 2 differs from rank 0 (rank 2's argument 4 is '--load', rank 0's '--approach')" \
    -n 2 "$cli" mpi-indent --n 64 --approach 5 : -n 1 "$cli" mpi-indent --n 64 --load 5
fi
refused commands 2 "$start: ranks 1, 2 differ from rank 0 (rank 1's argument 1 is 'run', rank 0's 'mpi-indent')" \
  -n 1 "$cli" mpi-indent --n 64 --approach 5 : -n 2 "$cli" run "$work/a.ini"

# Scenes: two scene files; the same file name read from two folders; the same arguments naming
# files of other bytes (each rank's /proc/self/fd/7 opened on another scene, differing only in
# their output folders, into which rank 1 used to write its members); a rank whose own wisdom file
# cannot be used (IM_FFTW_WISDOM, a folder, on rank 1 only: the other rank used to wait forever).
export IM_FFTW_WISDOM="$work/wisdom"
scene() { # scene FILE OUTPUT
  printf '[scene]\nname = s\noutput = %s\n[surfaces]\nn = 32\nhurst = 0.8\nlambda_s = 4\nslopes = 0.08\nseeds = 1:2\n' "$2" > "$1"
  printf '[punch]\nshape = cone\nalpha = 80\n[loading]\nload_star = 100\ncontrol = load\nsteps = 50:100:2\n[output]\ntable = yes\n' >> "$1"
}
mkdir -p "$work/d1" "$work/d2"
scene "$work/a.ini" "$work/out_a"
scene "$work/b.ini" "$work/out_b"
scene "$work/d1/s.ini" "$work/out_a"
scene "$work/d2/s.ini" "$work/out_a"
refused scenes 2 "$start: rank 1 differs from rank 0 (rank 1's argument 2 is '$work/b.ini', rank 0's '$work/a.ini')" \
  -n 1 "$cli" run "$work/a.ini" : -n 1 "$cli" run "$work/b.ini"
refused folders 2 "$start: rank 1 differs from rank 0 (rank 1 runs in the folder $work/d2, rank 0 in $work/d1)" \
  -n 1 -wdir "$work/d1" "$cli" run s.ini : -n 1 -wdir "$work/d2" "$cli" run s.ini
refused scene_bytes 2 "/proc/self/fd/7: rank 1 reads other bytes from it than rank 0: every rank must read the same file" \
  -n 1 bash -c "exec '$cli' run /proc/self/fd/7 7< '$work/a.ini'" : -n 1 bash -c "exec '$cli' run /proc/self/fd/7 7< '$work/b.ini'"
[ ! -e "$work/out_a" ] && [ ! -e "$work/out_b" ] || fail "scenes of other bytes: a rank wrote $(ls -d "$work"/out_*)"
refused one_rank 2 "rank 1: IM_FFTW_WISDOM $work: wisdom file $work: .* is not a regular file" \
  -n 1 "$cli" run "$work/a.ini" : -n 1 -x IM_FFTW_WISDOM="$work" "$cli" run "$work/a.ini"
"$mpiexec" -n 2 --oversubscribe "$cli" run "$work/a.ini" > /dev/null 2> "$work/alike.err" || fail "a scene on 2 ranks: $(cat "$work/alike.err")"
[ -s "$work/out_a/table1.csv" ] || fail "a scene on 2 ranks wrote no table1.csv"

# Files a scene names, the same path on every rank but other files on each (a node-local path): its
# surface file surf.npy is a link to /proc/self/fd/8, which each rank opens on another surface. Rank 1
# solves member 1 (surf.npy) from its own bytes: results of two surfaces under one name in run.json.
for seed in 1 2 3; do "$cli" surface --n 32 --seed $seed --out "$work/h$seed.npy" > /dev/null || fail "surface $seed"; done
ln -s /proc/self/fd/8 "$work/surf.npy"
printf '[scene]\nname = f\noutput = %s\n[surfaces]\nfile = h3.npy, surf.npy\n[loading]\nload_star = 100\n[output]\ntable = yes\n' \
  "$work/out_f" > "$work/f.ini"
on_fd8() { echo "exec '$cli' run '$work/f.ini' 8< '$1'"; } # on_fd8 FILE: the rank's command, its fd 8 on FILE
refused input_bytes 2 "$work/surf.npy (\[surfaces\] file): rank 1 reads other bytes from it than rank 0: every rank must read the same file" \
  -n 1 bash -c "$(on_fd8 "$work/h1.npy")" : -n 1 bash -c "$(on_fd8 "$work/h2.npy")"
[ ! -e "$work/out_f" ] || fail "surface files of other bytes: a rank wrote $(ls "$work/out_f")"
refused input_missing 2 "rank 1: .*surf.npy" -n 1 bash -c "$(on_fd8 "$work/h1.npy")" : -n 1 "$cli" run "$work/f.ini"
# mpi-indent's --surface, the same link on both ranks onto other surfaces: refused naming it, nothing written.
indent_fd8() { echo "exec '$cli' mpi-indent --surface '$work/surf.npy' --approach 1 --out '$work/out_s' 8< '$1'"; }
refused surface_bytes 2 "$work/surf.npy (--surface): rank 1 reads other bytes from it than rank 0: every rank must read the same file" \
  -n 1 bash -c "$(indent_fd8 "$work/h1.npy")" : -n 1 bash -c "$(indent_fd8 "$work/h2.npy")"
[ ! -e "$work/out_s" ] || fail "a --surface of other bytes: a rank wrote $(ls "$work/out_s")"
"$mpiexec" -n 2 --oversubscribe bash -c "$(on_fd8 "$work/h1.npy")" > /dev/null 2> "$work/alike_files.err" ||
  fail "a scene of files alike on 2 ranks: $(cat "$work/alike_files.err")"
[ -s "$work/out_f/table1.csv" ] || fail "a scene of files alike on 2 ranks wrote no table1.csv"
echo "cli_mpi: ok"
