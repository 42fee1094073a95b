#!/usr/bin/env bash
# How `indentmap indent` writes its folder: it takes the folder's lock as scenes do, removes the
# field files an earlier run left there (keeping inputs), appends history.csv line by line so that
# a killed run leaves only whole lines, and writes run.json for a path that is not UTF-8.
set -u
cli=$1
dir=$(mktemp -d)
trap 'kill "$pid" 2>/dev/null; rm -rf "$dir"' EXIT
pid=
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=1
cd "$dir" || exit 1
"$cli" surface --n 32 --seed 5 --out s.npy >/dev/null || exit 1

# a second run into a folder in use stops at once
"$cli" indent --smooth --n 128 --approach 0.1:3:400 --out busy >/dev/null 2>&1 &
pid=$!
for _ in $(seq 2000); do [ -s busy/.lock ] && break; sleep 0.005; done
check "indent: a folder in use is refused" expect_exit 1 "output folder busy is in use by another indentmap run (pid $pid" \
  "$cli" indent s.npy --approach 1 --out busy
kill -KILL "$pid"
wait "$pid" 2>/dev/null
pid=
check "indent: killed mid-run, history.csv holds whole lines only" \
  awk -F, 'NR == 1 { columns = NF } NR > 1 && (NF != columns || $1 != NR - 1) { bad = 1 } END { exit bad || NR < 2 }' busy/history.csv
# run.json is written as the run starts, "running": a killed run (SIGKILL, the OOM killer) left none, and
# with it no record of its surface and options beside the rows
check "indent: killed mid-run, run.json says it was running" grep -q '"status": "running"' busy/run.json
check "... with its arguments" grep -q '"--approach",' busy/run.json
check "indent: the stale lock of a killed run is taken over" expect_exit 0 "taking over the stale lock" \
  "$cli" indent s.npy --approach 1 --out busy
check "... and removed at the end" test ! -e busy/.lock

# a rerun removes the earlier run's field files, but not an input among them
"$cli" indent s.npy --approach 0.5:1:3 --fields --out re >/dev/null || exit 1
"$cli" indent s.npy --approach 0.5:1:2 --fields --out re >/dev/null
check "rerun with fewer steps: no field of step 3 left" bash -c "! ls re | grep -q _0003.npy"
check "... its own fields written" test -s re/force_0002.npy -a -s re/gap_0002.npy -a -s re/displacement_0002.npy
check "... history.csv of the new run" test "$(wc -l <re/history.csv)" -eq 3
cp s.npy re/force_0007.npy
"$cli" indent re/force_0007.npy --approach 1 --out re >/dev/null
check "rerun without --fields: earlier fields removed" bash -c "! ls re | grep -q '^gap_\|^displacement_\|force_0001'"
check "... the input among them kept" cmp s.npy re/force_0007.npy

# history.csv: one line per step, each step's values as printed
"$cli" indent --smooth --n 32 --approach 0.001:2:300 --out many >/dev/null
check "history.csv: 300 steps, numbered" awk -F, 'NR > 1 && $1 != NR - 1 { bad = 1 } END { exit bad || NR != 301 }' \
  many/history.csv

# a path that is not UTF-8: run.json is written, the path escaped and marked so
odd=$'odd\xff\xfe'
mkdir "$odd" && cp s.npy "$odd/"
check "a surface path that is not UTF-8" bash -c "'$cli' indent '$odd/s.npy' --approach 0.5 --out '$odd/out' >/dev/null"
check "... run.json records it escaped" grep -q '"source": "odd\\\\xff\\\\xfe/s.npy"' "$odd/out/run.json"
check "... and says so" grep -q '"source_encoding": "escaped"' "$odd/out/run.json"
printf '[scene]\noutput = out2\n[surfaces]\nn = 32\n[loading]\ncontrol = displacement\nsteps = 0.5, 1\n[output]\nplots = fig5\n' \
  >"$odd/scene.ini"
check "a scene path that is not UTF-8" bash -c "'$cli' run --quiet '$odd/scene.ini' >/dev/null"
check "... its run.json says so" grep -q '"scene_encoding": "escaped"' "$odd/out2/run.json"
check "... in its contents too" grep -q '"scene_file_encoding": "escaped"' "$odd/out2/run.json"
"$cli" run --from-record "$odd/out2/run.json" --out again >/dev/null 2>err
check "--from-record refuses a record whose scene path was escaped" test $? -eq 2
check "... saying why" grep -q "is a path that was not UTF-8, recorded escaped" err
finish
