#!/usr/bin/env bash
# Concurrent runs: two runs of one ensemble into different output folders at the same time give
# byte for byte the table and histories of a run alone; a second run into a folder in use is
# refused with the folder and the first run's pid, and the first one is unaffected; a lock left by
# a process that died is taken over with a warning; the lock file is gone after every run.
set -u
cli=$1
dir=$(mktemp -d)
pids=()
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done; rm -rf "$dir"' EXIT
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=2

scene() { ensemble_scene "$dir/$1.ini" "$1" "$2"; }
scene alone alone
scene a a
scene b b
scene same same

"$cli" run --quiet "$dir/alone.ini" >/dev/null 2>&1
check "run alone" test $? -eq 0
check "no lock left" test ! -e "$dir/alone/.lock"

# Two folders at once.
"$cli" run --quiet "$dir/a.ini" >/dev/null 2>"$dir/a.log" & pids+=($!)
"$cli" run --quiet "$dir/b.ini" >/dev/null 2>"$dir/b.log" & pids+=($!)
wait "${pids[0]}"; check "first of two at once" test $? -eq 0
wait "${pids[1]}"; check "second of two at once" test $? -eq 0
pids=()
for out in a b; do
  check "$out: table1.csv as alone" cmp -s "$dir/alone/table1.csv" "$dir/$out/table1.csv"
  for f in "$dir"/alone/histories/*.csv; do
    check "$out: $(basename "$f") as alone" cmp -s <(history_rows "$f") <(history_rows "$dir/$out/histories/$(basename "$f")")
  done
  check "$out: no lock left" test ! -e "$dir/$out/.lock"
done

# One folder twice: the second waits for the first's lock file, then is refused.
"$cli" run --quiet "$dir/same.ini" >/dev/null 2>"$dir/first.log" & pids+=($!)
for _ in $(seq 1200); do [ -s "$dir/same/.lock" ] && break; sleep 0.01; done
"$cli" run --quiet "$dir/same.ini" >/dev/null 2>"$dir/second.log"
check "second run into the same folder exits 1" test $? -eq 1
check "refusal names the folder and the pid" grep -q "output folder $dir/same is in use by another indentmap run (pid ${pids[0]}" "$dir/second.log"
wait "${pids[0]}"; check "first run unaffected" test $? -eq 0
pids=()
check "same folder: table1.csv as alone" cmp -s "$dir/alone/table1.csv" "$dir/same/table1.csv"
check "same folder: no lock left" test ! -e "$dir/same/.lock"

# A stale lock: the pid of a process that has ended.
true & dead=$!
wait "$dead"
echo "$dead" >"$dir/same/.lock"
"$cli" run --quiet --resume "$dir/same.ini" >/dev/null 2>"$dir/stale.log"
check "stale lock taken over" test $? -eq 0
check "stale lock warning names the pid" grep -q "taking over the stale lock $dir/same/.lock of pid $dead" "$dir/stale.log"
check "stale lock removed" test ! -e "$dir/same/.lock"

# A lock held by another live process (flock(1), as another run would hold it).
if command -v flock >/dev/null; then
  flock "$dir/same/.lock" sleep 30 & pids+=($!)
  for _ in $(seq 500); do flock -n "$dir/same/.lock" true || break; sleep 0.01; done
  "$cli" run --quiet --resume "$dir/same.ini" >/dev/null 2>"$dir/held.log"
  check "held lock refused" test $? -eq 1
  check "held lock message" grep -q "is in use by another indentmap run" "$dir/held.log"
  kill "${pids[0]}"; wait "${pids[0]}" 2>/dev/null; pids=()
fi

finish
