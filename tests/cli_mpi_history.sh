#!/usr/bin/env bash
# indentmap mpi-indent's histories of the half-space (MPI builds; skipped, exit 77, elsewhere): --approach LIST
# and --load LIST, repulsive, with --hardness (plastic memory from step to step) and adhesive with --hardness, by
# a profile punch (--profile: an axisymmetric table and a 2-D field),
# against indent --full on a 64 x 48 rough surface: every column of history.csv (history_compare.sh: counts
# exact, values to 1e-9), the same bytes on 1 and 3 ranks but for the seconds, the Oliver-Pharr table where
# there is an unloading branch, run.json's control and targets; a capped history whose unloading does not
# retrace its loading. Refused with one message and exit 2: a bad list, a tension without adhesion.
#   cli_mpi_history.sh PATH_TO_INDENTMAP [adhesive-load]
# With adhesive-load, the slow case alone: adhesion under load control (indent's forward walk of the approach;
# on 3 oversubscribed ranks each of its many trial solves waits in the passes' collectives).
set -uo pipefail
cli=$1
source "$(dirname "$0")/mpi/cli_history.sh"

"$cli" surface --n 64 --m 48 --seed 3 --out "$work/p.npy" > /dev/null || fail "surface"

# same_history NAME ARGUMENTS...: indent --full's history and mpi-indent's on 1 and 3 ranks (and those of
# $more_ranks) at --tol $tol (DIR/NAME.serial, NAME.1, NAME.3)
tol=1e-8 more_ranks=""
same_history() {
  local name=$1
  shift
  "$cli" indent "$work/p.npy" --full "$@" --tol $tol --out "$work/$name.serial" > /dev/null 2> "$work/$name.err" ||
    fail "$name: indent: $(cat "$work/$name.err")"
  for k in 1 3 $more_ranks; do
    timeout 600 "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --surface "$work/p.npy" "$@" --tol $tol \
      --out "$work/$name.$k" > "$work/$name.$k.csv" 2> "$work/$name.$k.err" ||
      fail "$name: mpi-indent on $k ranks (exit $?, 124: timed out): $(cat "$work/$name.$k.err")"
    cut -d, -f1-10,12- "$work/$name.$k.csv" > "$work/$name.$k.cut"
  done
  history_differences "$work/$name.serial/history.csv" "$work/$name.1/history.csv" > "$work/$name.diff" ||
    fail "$name: mpi-indent's history is not indent's: $(head -5 "$work/$name.diff")"
  for k in 3 $more_ranks; do
    cmp -s "$work/$name.1.cut" "$work/$name.$k.cut" ||
      fail "$name: 1 and $k ranks differ: $(diff "$work/$name.1.cut" "$work/$name.$k.cut")"
  done
  cmp -s "$work/$name.3.csv" "$work/$name.3/history.csv" || fail "$name: history.csv is not stdout"
  if [ -e "$work/$name.serial/indentation.csv" ]; then # Oliver-Pharr's table of the unloading branches
    history_differences "$work/$name.serial/indentation.csv" "$work/$name.3/indentation.csv" > "$work/$name.diff" ||
      fail "$name: indentation.csv is not indent's: $(head -5 "$work/$name.diff")"
  fi
  python3 -c 'import json, sys
s, m = (json.load(open(p)) for p in sys.argv[1:3])
keys = ("control", "targets", "steps_completed", "indentation", "periodic")
sys.exit(not (all(s[k] == m[k] for k in keys) and m["ranks"] == 3))' \
    "$work/$name.serial/run.json" "$work/$name.3/run.json" || fail "$name: run.json: $(head -c 1500 "$work/$name.3/run.json")"
  [ -s "$work/$name.3/force.npy" ] && [ -s "$work/$name.3/gap.npy" ] || fail "$name: no last step's fields"
}

# column NAME CSV ROW: the value of a column of history.csv (row 1 the first step)
column() {
  awk -F, -v want="$1" -v row="$3" 'NR == 1 { for (c = 1; c <= NF; ++c) if ($c == want) at = c; next }
    NR - 1 == row { print $at }' "$2"
}

# unloading_differs NAME COLUMN LOADING UNLOADING: the capped history's unloading step (same target as its loading
# step) does not retrace the loading: COLUMN (a load, or under load control an approach) differs by over 1% (the same to the tolerance without memory),
# and the plastic depth stays
unloading_differs() {
  local csv="$work/$1.3/history.csv" on off
  on=$(column "$2" "$csv" "$3") off=$(column "$2" "$csv" "$4")
  awk -v a="$on" -v b="$off" 'BEGIN { d = a - b; s = a < 0 ? -a : a; if (d < 0) d = -d; exit !(d > 0.01 * s) }' ||
    fail "$1: the unloading step $4 retraces the loading step $3 ($2 $on and $off): no plastic memory"
  [ "$(column plastic_depth "$csv" "$3")" != 0 ] &&
    [ "$(column plastic_depth "$csv" "$4")" = "$(column plastic_depth "$csv" $(($3 + 1)))" ] ||
    fail "$1: the plastic depth is not kept: $(cut -d, -f1-3,22- "$csv")"
}

if [ "${2:-}" = adhesive-load ]; then
  # the walk ends within tol of the load or tol apart in the approach, where a steep N(w) leaves the load
  # 1e-7 from the target at tol 1e-8 (serially and over ranks, 5e-8 apart): compared at 1e-9, solved at 1e-10
  tol=1e-10
  same_history adhesive_load --load 1,5,1,-0.5,-1 --adhesion-work 0.02 --adhesion-range 0.2
  echo "mpi-indent's adhesive load-controlled history is indent's on 1 and 3 ranks"
  exit 0
fi

# Under the sanitizers (CMake sets IM_SANITIZED=1 in that build, where each mpirun takes 5-15 s of Open MPI's start
# and LeakSanitizer's exit checks) these three are left to the plain pass: the later cases run their C paths over
# the same ranks (--approach LIST: profile's, the same targets; --load LIST: profile_2d's and capped_loads'; the
# cap's memory: capped_loads' and adhesive_capped's, the same hardness).
if [ "${IM_SANITIZED:-0}" != 1 ]; then
  same_history approaches --approach 0.5,1.5,3,1.5,0.5
  # also on 4 ranks: rank 0, which prints, then holds the rows above the axis only (FFTW-MPI's slabs of the 96
  # padded rows), not the deepest patch (seen to fail there with the plastic extremes not reduced over the ranks)
  more_ranks=4 same_history capped --approach 0.5,1.5,3,1.5,0.5 --hardness 0.12
  unloading_differs capped load 2 4
  same_history loads --load 2,10,30,10,2
fi
same_history capped_loads --load 2,10,30,10,2 --hardness 0.12
unloading_differs capped_loads approach 2 4
# the profile punch (--profile, read on every rank), a tabulated paraboloid z = r^2 / 40 and a 2-D field (elliptic
# paraboloid around its centre sample, not axisymmetric)
awk 'BEGIN { print "# r z"; for (i = 0; i <= 40; ++i) print i, i * i / 40 }' > "$work/profile.txt"
same_history profile --approach 0.5,1.5,3,1.5,0.5 --punch profile --profile "$work/profile.txt"
python3 -c 'import struct, sys
ny, nx = 21, 31
header = "{\x27descr\x27: \x27<f8\x27, \x27fortran_order\x27: False, \x27shape\x27: (%d, %d), }" % (ny, nx)
header += " " * (118 - len(header)) + "\n"
z = [((x - 15) ** 2 + 2 * (y - 10) ** 2) / 40 for y in range(ny) for x in range(nx)]
open(sys.argv[1], "wb").write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() +
                              struct.pack("<%dd" % len(z), *z))' "$work/profile_2d.npy" || fail "profile_2d.npy"
same_history profile_2d --load 2,10,25 --punch profile --profile "$work/profile_2d.npy"
# (at --hardness 0.15 and 0.2 the deeper step took 1 and 3 more of its ~1500 iterations over ranks than serially,
# its loads 4e-13 apart: the passes' stopping rules met at rounding level, the serial solver summing a few patches
# directly where the ranks recompute u; docs/mpi.md)
same_history adhesive_capped --approach 0.5,2,0.5,0,-0.1,-0.2 --adhesion-work 0.02 --adhesion-range 0.2 \
  --hardness 0.12
unloading_differs adhesive_capped load 1 3

refused bad_loads "--load '2,x': 'x' is not a number" --load 2,x
refused tension "--load '2,-1'" --load 2,-1 --hardness 0.1
refused profile_alone "--punch profile and --profile FILE go together" --approach 1 --punch profile
refused profile_on_cell "--profile are the half-space's" --periodic --pressure 0.1 --profile "$work/profile.txt"
# A step whose first touch lies on the edge, refused before its solve over the ranks as serially (U7): the smooth
# surface under a flat face past the edge, on 3 ranks (the edge row 0 on rank 0, row 63 on another).
timeout 300 "$mpiexec" -n 3 --oversubscribe "$cli" mpi-indent --n 64 --slope 0 --punch flat --radius 40 \
  --approach 0.5,1 > /dev/null 2> "$work/first_touch.err"
status=$?
[ $status -eq 1 ] || fail "first touch on the edge: exit $status, expected 1: $(cat "$work/first_touch.err")"
grep -qF "approach 0.5 cannot be reached on the 64 x 64 surface without contact at its edge: the flat punch first touches the surface on the edge, at patch (8, 0)" "$work/first_touch.err" ||
  fail "first touch on the edge: not refused before solving: $(cat "$work/first_touch.err")"
# Radius 31.5: the first edge patch in row-major order is on column 63, row 27, on a middle rank, as serially
# (cli_stability; the serial search once took row 63 before column 63's rows and named (27, 63)).
timeout 300 "$mpiexec" -n 3 --oversubscribe "$cli" mpi-indent --n 64 --slope 0 --punch flat --radius 31.5 \
  --approach 0.5,1 > /dev/null 2> "$work/first_touch_side.err"
grep -qF "at patch (63, 27), so any step beyond that touch has contact there (its face's radius 31.5 reaches that patch's centre, 31.4006 from its axis)" "$work/first_touch_side.err" ||
  fail "first touch on the side: $(cat "$work/first_touch_side.err")"
echo "mpi-indent's histories of the half-space are indent's on 1 and 3 ranks"
