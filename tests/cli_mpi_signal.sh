#!/usr/bin/env bash
# indentmap mpi-indent under a signal (MPI builds; skipped, exit 77, elsewhere): SIGTERM to every rank during a
# history stops every rank before the same step or at the same iteration, keeps the steps done (history.csv's
# rows whole, run.json "interrupted" with their count), says so once on rank 0 and exits 128 + 15; no temporary
# file is left (findings-recheck.md, redteam6 M1: the ranks died of the signal, no run.json, not a word).
#   cli_mpi_signal.sh PATH_TO_INDENTMAP
set -uo pipefail
cli=$1
"$cli" --help | grep -q mpi-indent || { echo "built without MPI: skipped"; exit 77; }
mpiexec=$(command -v mpiexec || command -v mpirun) || { echo "no mpiexec: skipped"; exit 77; }
source "$(dirname "$0")/mpi/open_mpi_env.sh"
export OMP_NUM_THREADS=1 IM_FFTW_WISDOM=
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }

# As tests/mpi/scene_ranks.sh: the ranks frozen once three steps are on disk (past their handlers), sent the
# SIGTERM mpirun would send, and thawed, so that the signal lands in the history however fast the machine;
# mpirun's kill timeout at 5 s lets a slow rank reach its check on a loaded machine.
OMPI_MCA_odls_base_sigkill_timeout=5 "$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 128 \
  --approach 1:10:200 --tol 1e-8 --out "$work/out" > "$work/stdout" 2> "$work/stderr" &
launcher=$!
for _ in $(seq 2400); do [ "$(wc -l < "$work/out/history.csv" 2>/dev/null || echo 0)" -gt 3 ] && break; sleep 0.05; done
ranks=$(pgrep -P $launcher)
[ "$(echo $ranks | wc -w)" = 2 ] || fail "the ranks under mpirun: '$ranks'"
kill -STOP $ranks
kill -TERM $ranks
kill -CONT $ranks
wait $launcher
status=$?
[ $status -ne 0 ] || fail "exit 0 after SIGTERM: $(cat "$work/stderr")"
[ "$(grep -c "interrupted by signal 15" "$work/stderr")" = 1 ] ||
  fail "expected one line 'interrupted by signal 15' on stderr: $(cat "$work/stderr")"
[ -f "$work/out/run.json" ] || fail "no run.json after the interruption: $(ls "$work/out")"
grep -q '"status": "interrupted"' "$work/out/run.json" || fail "run.json's status: $(cat "$work/out/run.json")"
rows=$(($(wc -l < "$work/out/history.csv") - 1))
[ "$rows" -ge 3 ] && [ "$rows" -lt 200 ] || fail "history.csv holds $rows steps"
grep -q "\"steps_completed\": $rows," "$work/out/run.json" ||
  fail "run.json's steps_completed against history.csv's $rows rows: $(grep steps_completed "$work/out/run.json")"
columns=$(head -1 "$work/out/history.csv" | awk -F, '{print NF}')
awk -F, -v c="$columns" 'NF != c { exit 1 }' "$work/out/history.csv" || fail "history.csv holds a partial row"
cmp -s "$work/stdout" "$work/out/history.csv" || fail "stdout and history.csv differ"
! find "$work/out" -name '*.tmp.*' | grep -q . || fail "temporary files left: $(ls "$work/out")"
echo "a history interrupted over ranks keeps its steps, its record says so, one message"
echo "cli_mpi_signal: ok"
