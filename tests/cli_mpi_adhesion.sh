#!/usr/bin/env bash
# indentmap mpi-indent --approach LIST --adhesion-work W --adhesion-range D (MPI builds; skipped, exit 77,
# elsewhere): the half-space's adhesive approach and retraction through the pull-off over ranks is indent's
# history on the whole surface (indent --full): every column of history.csv (the same iterations and patch
# counts; loads, tensile forces and the theory beside them to 1e-9; seconds and convolutions, which the MPI
# solver spends otherwise, aside; residuals to 1e-3 of theirs), run.json's pull-off, jumps and lost work, and
# the same bytes on 1 and 3 ranks but for the seconds. Refused with one clear message: a negative single
# approach, a bad list (a cell's adhesion under mean pressures or with a hardness: cli_mpi.sh).
#   cli_mpi_adhesion.sh PATH_TO_INDENTMAP
set -uo pipefail
cli=$1
source "$(dirname "$0")/mpi/cli_history.sh"

"$cli" surface --n 64 --m 48 --seed 3 --out "$work/p.npy" > /dev/null || fail "surface"
steps=(--approach 0.5,2,0.5,0,-0.1,-0.2,-0.3 --adhesion-work 0.02 --adhesion-range 0.2 --tol 1e-8)
"$cli" indent "$work/p.npy" --full "${steps[@]}" --out "$work/serial" > "$work/serial.out" 2> "$work/serial.err" ||
  fail "indent: $(cat "$work/serial.err")"
for k in 1 3; do
  timeout 300 "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --surface "$work/p.npy" "${steps[@]}" \
    --out "$work/mpi$k" > "$work/mpi$k.csv" 2> "$work/mpi$k.err" ||
    fail "mpi-indent on $k ranks (exit $?, 124: timed out): $(cat "$work/mpi$k.err")"
  cut -d, -f1-10,12- "$work/mpi$k.csv" > "$work/mpi$k.cut"
done

history_differences "$work/serial/history.csv" "$work/mpi1.csv" > "$work/diff" ||
  fail "mpi-indent's history is not indent's: $(head -5 "$work/diff")"
cmp -s "$work/mpi1.cut" "$work/mpi3.cut" || fail "1 and 3 ranks differ: $(diff "$work/mpi1.cut" "$work/mpi3.cut")"
cmp -s "$work/mpi3.csv" "$work/mpi3/history.csv" || fail "history.csv is not stdout"

# the history goes into tension and out of contact: a pull-off and a jump-out, the same as indent's
summary() { # summary RUN_JSON: the adhesion block's pull-off force and approach, jumps and lost work
  python3 -c 'import json, sys
a = json.load(open(sys.argv[1]))["adhesion"]
print(" ".join("%.10g" % a[k] if a[k] is not None else "none" for k in
      ("pull_off_force", "pull_off_approach", "jump_in_approach", "jump_out_approach", "work_done", "hysteresis_work")))' "$1"
}
serial_summary=$(summary "$work/serial/run.json") mpi_summary=$(summary "$work/mpi3/run.json")
[ "$serial_summary" = "$mpi_summary" ] || fail "run.json's adhesion: indent's '$serial_summary', mpi-indent's '$mpi_summary'"
awk -v s="$serial_summary" 'BEGIN { split(s, v, " "); exit !(v[1] > 0 && v[4] != "none") }' ||
  fail "expected a pull-off force and a jump-out: $serial_summary"
python3 -c 'import json, sys
r = json.load(open(sys.argv[1]))
sys.exit(not (r["periodic"] is False and r["control"] == "approach" and r["punch"] == {"kind": "cone", "alpha_degrees": 80}
              and r["ranks"] == 3 and r["steps_completed"] == 7))' "$work/mpi3/run.json" ||
  fail "run.json: $(head -c 2000 "$work/mpi3/run.json")"
[ -s "$work/mpi3/force_distance.png" ] || fail "no force_distance.png"
# ... and said in indent's words, on stderr beside the CSV (findings R7: run.json only): the same line, the
# same numbers, but for the folder named
said() { grep '^adhesion: ' "$1" | sed "s|; $2/force_distance.png and .pdf\$||"; }
serial_said=$(said "$work/serial.out" "$work/serial") mpi_said=$(said "$work/mpi3.err" "$work/mpi3")
[ -n "$serial_said" ] && [ "$serial_said" = "$mpi_said" ] ||
  fail "the adhesion line: indent's '$serial_said', mpi-indent's '$mpi_said'"
[ -s "$work/mpi3/force.npy" ] && [ -s "$work/mpi3/gap.npy" ] || fail "no last step's fields"

# --adhesion-zone as indent's: the widened law (l = 0.79 patches widened to 2), the same history on one rank
"$cli" indent "$work/p.npy" --full "${steps[@]}" --adhesion-zone 2 --out "$work/zone" > /dev/null 2> "$work/zone.err" ||
  fail "indent --adhesion-zone: $(cat "$work/zone.err")"
timeout 300 "$mpiexec" -n 1 "$cli" mpi-indent --surface "$work/p.npy" "${steps[@]}" --adhesion-zone 2 \
  > "$work/mpi-zone.csv" 2> "$work/mpi-zone.err" || fail "mpi-indent --adhesion-zone: $(cat "$work/mpi-zone.err")"
history_differences "$work/zone/history.csv" "$work/mpi-zone.csv" > "$work/diff" ||
  fail "mpi-indent --adhesion-zone's history is not indent's: $(head -5 "$work/diff")"
! cmp -s "$work/mpi-zone.csv" "$work/mpi1.csv" || fail "--adhesion-zone 2 changed nothing"
grep -q '^adhesion: pull-off force ' "$work/mpi-zone.err" && ! grep -q force_distance "$work/mpi-zone.err" ||
  fail "without --out: expected the adhesion line, naming no figure: $(cat "$work/mpi-zone.err")"
refused zone_alone "--adhesion-zone widens the zone of --adhesion-work" --approach 0.5 --adhesion-zone 1

refused negative "--approach = -0.5: expected a number in \[0," --approach -0.5
refused bad_list "--approach '0.5,x': 'x' is not a number" --approach 0.5,x --adhesion-work 0.02 --adhesion-range 0.2
echo "mpi-indent's adhesive history is indent's on 1 and 3 ranks"
