#!/usr/bin/env bash
# Interrupted scenes: a reduced ensemble (128 x 128, 8 surfaces, a table and histories) is stopped
# with SIGINT once its first table member is on disk, resumed and stopped with SIGTERM once its
# first history is on disk, then resumed to the end. Checks the exit statuses (130, 143), that no
# temporary file remains, that what was kept is read back rather than solved again (the kept files,
# whose seconds column would change, are unchanged), and that the final table1.csv and histories
# are byte for byte those of an uninterrupted run with the same thread count (each surface is
# solved on one thread, so the order in which surfaces finish does not change any number).
# run.json says where each run stands: "interrupted" (with the message) after a signal, "ok" at the end,
# since a stopped run leaves the folder's tables and figures as they were. Last, `indentmap indent`
# stopped with SIGINT between two steps.
set -u
cli=$1
dir=$(mktemp -d)
trap 'kill "$pid" 2>/dev/null; rm -rf "$dir"' EXIT
pid=
source "$(dirname "$0")/lib.sh"
export OMP_NUM_THREADS=2

scene() { ensemble_scene "$dir/$1.ini" "$1" "$1" 1e-8; }
scene whole
scene cut

"$cli" run --quiet "$dir/whole.ini" >/dev/null 2>"$dir/whole.log"
check "uninterrupted run" test $? -eq 0

# Starts a run in the background, waits for a file matching the pattern (at most 60 s), then sends
# the signal; the run's exit status goes to $dir/status.
run_and_kill() {
  local signal=$1 pattern=$2; shift 2
  "$cli" run --quiet "$@" "$dir/cut.ini" >/dev/null 2>"$dir/cut.log" &
  pid=$!
  for _ in $(seq 1200); do
    compgen -G "$dir/cut/$pattern" >/dev/null && break
    sleep 0.05
  done
  kill "-$signal" "$pid"
  wait "$pid"
  echo $? >"$dir/status"
  pid=
}
no_temporary_files() { ! find "$dir/cut" -name '*.tmp.*' | grep -q .; }
members() { find "$dir/cut/$1" -name 'member_*.csv' 2>/dev/null | wc -l; }

run_and_kill INT 'table/member_*.csv'
check "SIGINT exits 130" test "$(cat "$dir/status")" -eq 130
check "SIGINT names the signal" grep -q "interrupted by signal 2" "$dir/cut.log"
check "no temporary files after SIGINT" no_temporary_files
check "no lock left after SIGINT" test ! -e "$dir/cut/.lock"
check "SIGINT kept a member" test "$(members table)" -ge 1
check "SIGINT stopped before the end" test ! -e "$dir/cut/table1.csv"
record_status() { python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); print(r["status"], r["error"])' "$1"; }
check "SIGINT: run.json says interrupted" bash -c "[[ '$(record_status "$dir/cut/run.json")' == 'interrupted interrupted by signal 2'* ]]"
mkdir "$dir/kept" && cp "$dir"/cut/table/member_*.csv "$dir/kept/"

run_and_kill TERM 'histories/member_*.csv' --resume
check "SIGTERM exits 143" test "$(cat "$dir/status")" -eq 143
check "no temporary files after SIGTERM" no_temporary_files
check "no lock left after SIGTERM" test ! -e "$dir/cut/.lock"
check "SIGTERM stopped before the end" test "$(members histories)" -lt 8

"$cli" run --quiet --resume "$dir/cut.ini" >/dev/null 2>"$dir/resume.log"
check "resume finishes" test $? -eq 0
check "no temporary files after resume" no_temporary_files
check "resume: run.json says ok" test "$(record_status "$dir/cut/run.json")" = "ok "
check "uninterrupted: run.json says ok" test "$(record_status "$dir/whole/run.json")" = "ok "
for f in "$dir"/kept/*.csv; do
  check "kept $(basename "$f") read back, not solved again" cmp -s "$f" "$dir/cut/table/$(basename "$f")"
done
check "table1.csv as uninterrupted" cmp "$dir/whole/table1.csv" "$dir/cut/table1.csv"
check "table1.md as uninterrupted" cmp "$dir/whole/table1.md" "$dir/cut/table1.md"
check "every history" test "$(members histories)" -eq 8
for f in "$dir"/whole/histories/*.csv; do
  check "history $(basename "$f") as uninterrupted" cmp <(history_rows "$f") <(history_rows "$dir/cut/histories/$(basename "$f")")
done

# indentmap indent: SIGINT between steps keeps the steps solved so far in history.csv.
"$cli" indent --smooth --n 128 --approach 1:40:400 --out "$dir/indent" >"$dir/indent.log" 2>&1 &
pid=$!
for _ in $(seq 1200); do
  [ -f "$dir/indent/history.csv" ] && [ "$(wc -l <"$dir/indent/history.csv")" -ge 3 ] && break
  sleep 0.05
done
kill -INT "$pid"
wait "$pid"
check "indent: SIGINT exits 130" test $? -eq 130
pid=
check "indent: names the signal" grep -q "interrupted by signal 2" "$dir/indent.log"
check "indent: no temporary files" bash -c "! find '$dir/indent' -name '*.tmp.*' | grep -q ."
check "indent: stopped part way" test "$(wc -l <"$dir/indent/history.csv")" -lt 401
check "indent: history holds every reported step" \
  test "$(wc -l <"$dir/indent/history.csv")" -eq "$(($(grep -c '^step' "$dir/indent.log") + 1))"

finish
