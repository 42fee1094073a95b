#!/usr/bin/env bash
# indentmap mpi-indent under a signal (MPI builds; skipped, exit 77, elsewhere): SIGTERM to every rank, or to one
# rank alone, during a history stops every rank before the same step or at the same iteration, keeps the steps
# done (history.csv's rows whole, run.json "interrupted" with their count, written before the frames are drawn:
# mpirun kills the ranks a second after passing a signal on), says so once on rank 0 and exits 128 + 15 through
# mpirun; no temporary file is left (findings-recheck.md, redteam6 M1: the ranks died of the signal, no run.json,
# not a word).
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

# The rank of process PID under mpirun.
rank_of() { tr '\0' '\n' < "/proc/$1/environ" | sed -n 's/^OMPI_COMM_WORLD_RANK=//p'; }

# What an interrupted history in OUT must hold, mpirun having exited with STATUS: one message, 128 + 15 passed on
# by mpirun, run.json "interrupted" with history.csv's whole rows, stdout the same rows, no temporary file.
check_interrupted() { # CASE OUT STATUS
  local case=$1 out=$2 status=$3
  [ "$status" = 143 ] || fail "$case: mpirun's exit $status, expected 128 + 15: $(cat "$work/stderr")"
  [ "$(grep -c "interrupted by signal 15" "$work/stderr")" = 1 ] ||
    fail "$case: expected one line 'interrupted by signal 15' on stderr: $(cat "$work/stderr")"
  [ -f "$out/run.json" ] || fail "$case: no run.json after the interruption: $(ls "$out")"
  grep -q '"status": "interrupted"' "$out/run.json" || fail "$case: run.json's status: $(cat "$out/run.json")"
  local rows=$(($(wc -l < "$out/history.csv") - 1))
  grep -q "\"steps_completed\": $rows," "$out/run.json" ||
    fail "$case: run.json's steps_completed against history.csv's $rows rows: $(grep steps_completed "$out/run.json")"
  local columns=$(head -1 "$out/history.csv" | awk -F, '{print NF}')
  awk -F, -v c="$columns" 'NF != c { exit 1 }' "$out/history.csv" || fail "$case: history.csv holds a partial row"
  cmp -s "$work/stdout" "$out/history.csv" || fail "$case: stdout and history.csv differ"
  ! find "$out" -name '*.tmp.*' | grep -q . || fail "$case: temporary files left: $(ls "$out")"
}

# 1. Every rank. As tests/mpi/scene_ranks.sh: the ranks frozen once three steps are on disk (past their handlers),
# sent the SIGTERM mpirun would send, and thawed, so that the signal lands in the history however fast the
# machine; mpirun's kill timeout at 5 s lets a slow rank reach its check on a loaded machine. With --frames, rank 0
# is frozen again as soon as it starts the frames (DIR/frames made): run.json must be there already. Not under the
# sanitizers, where rank 0's drawing deadlocks in llvmpipe (CMakeLists.txt, cli_mpi_figures): there without frames.
frames=--frames
[ "${IM_SANITIZED:-0}" != 1 ] || frames=
# Each case's bound on mpirun (a hang is what case 2 looks for): 120 s, 300 s under the sanitizers, where Open MPI's
# start and LeakSanitizer's exits take seconds per rank on a loaded machine.
limit=120
[ "${IM_SANITIZED:-0}" != 1 ] || limit=300
# An earlier, completed history in the same folder: its force.npy, gap.npy and force_map.npy must not be left
# there as the interrupted run's (they were: only a completed history writes its last step's fields).
timeout $limit "$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 128 --approach 1,2 --map 4 --out "$work/out" \
  > /dev/null 2> "$work/stderr" || fail "the earlier, completed history: $(cat "$work/stderr")"
for field in force gap force_map; do [ -f "$work/out/$field.npy" ] || fail "the completed history wrote no $field.npy"; done
grep -A3 '"fields"' "$work/out/run.json" | grep -q '"force_map.npy"' ||
  fail "the completed history's run.json names no fields: $(grep -A3 '"fields"' "$work/out/run.json")"
OMPI_MCA_odls_base_sigkill_timeout=5 timeout $limit "$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 128 \
  --approach 1:10:200 --tol 1e-8 $frames --out "$work/out" > "$work/stdout" 2> "$work/stderr" &
launcher=$!
# (the earlier history's file has 2 rows, 3 lines: this waits for the new run's third row)
for _ in $(seq 2400); do [ "$(wc -l 2>/dev/null < "$work/out/history.csv" || echo 0)" -gt 3 ] && break; sleep 0.05; done
ranks=$(pgrep -P "$(pgrep -P $launcher)")
[ "$(echo $ranks | wc -w)" = 2 ] || fail "the ranks under mpirun: '$ranks'"
for pid in $ranks; do [ "$(rank_of $pid)" = 0 ] && rank0=$pid; done
kill -STOP $ranks
kill -TERM $ranks
kill -CONT $ranks
if [ -n "$frames" ]; then
  for _ in $(seq 12000); do [ -d "$work/out/frames" ] || ! kill -0 $rank0 2>/dev/null && break; sleep 0.01; done
  kill -STOP $rank0 2>/dev/null
  cp "$work/out/run.json" "$work/run_before_frames.json" 2>/dev/null || fail "no run.json when the frames began"
  kill -CONT $rank0 2>/dev/null
fi
wait $launcher
check_interrupted "SIGTERM to every rank" "$work/out" $?
for field in force gap force_map; do
  [ ! -e "$work/out/$field.npy" ] || fail "the earlier run's $field.npy left beside the interrupted run's record"
done
grep -q '"fields": \[\]' "$work/out/run.json" || fail "the interrupted run's fields: $(grep fields "$work/out/run.json")"
if [ -n "$frames" ]; then
  grep -q '"status": "interrupted"' "$work/run_before_frames.json" ||
    fail "run.json before the frames: $(cat "$work/run_before_frames.json")"
  [ "$(ls "$work/out/frames" | grep -c '^contact_.*\.png$')" = "$(($(wc -l < "$work/out/history.csv") - 1))" ] ||
    fail "a frame per step done expected: $(ls "$work/out/frames")"
fi

# 2. Rank 1 alone (as a user's kill of one process): the ranks must agree to stop (an MPI_Allreduce of the flags
# before each step, the solver's each iteration), or they wait for each other in collectives that never match;
# timeout ends such a hang. The signal is sent as soon as rank 1's handler is installed (SigCgt), so that it lands
# before a step as often as inside one.
timeout $limit "$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 256 --approach 1:10:200 --tol 1e-8 \
  --out "$work/one" > "$work/stdout" 2> "$work/stderr" &
launcher=$!
rank1=
for _ in $(seq 6000); do
  for pid in $(pgrep -P "$(pgrep -P $launcher)"); do [ "$(rank_of $pid 2>/dev/null)" = 1 ] && rank1=$pid; done
  [ -n "$rank1" ] && break
  sleep 0.01
done
[ -n "$rank1" ] || fail "no rank 1 under mpirun"
caught() { (( 0x$(sed -n 's/^SigCgt:\t//p' "/proc/$rank1/status" 2>/dev/null || echo 0) & (1 << 14) )); }
for _ in $(seq 6000); do caught && break; sleep 0.01; done
kill -TERM $rank1
wait $launcher
status=$?
[ $status != 124 ] || fail "SIGTERM to rank 1 alone: hung (timeout): $(cat "$work/stderr")"
check_interrupted "SIGTERM to rank 1 alone" "$work/one" $status
# 3. run.json cannot be written (a folder in its place, made while the ranks are frozen): its failure on a line of
# its own, and still the step's message (the record's error had replaced it: not a word of the interruption).
timeout $limit "$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 64 --approach 1:10:200 --tol 1e-8 \
  --out "$work/norecord" > "$work/stdout" 2> "$work/stderr" &
launcher=$!
for _ in $(seq 2400); do [ "$(wc -l 2>/dev/null < "$work/norecord/history.csv" || echo 0)" -gt 3 ] && break; sleep 0.05; done
ranks=$(pgrep -P "$(pgrep -P $launcher)")
[ "$(echo $ranks | wc -w)" = 2 ] || fail "run.json unwritable: the ranks under mpirun: '$ranks'"
kill -STOP $ranks
mkdir -p "$work/norecord/run.json/kept" || fail "run.json unwritable: could not put a folder in its place"
kill -TERM $ranks
kill -CONT $ranks
wait $launcher
status=$?
[ $status = 143 ] || fail "run.json unwritable: mpirun's exit $status, expected 143: $(cat "$work/stderr")"
grep -q "^indentmap: .*run.json" "$work/stderr" || fail "run.json unwritable: not said: $(cat "$work/stderr")"
[ "$(grep -c "interrupted by signal 15" "$work/stderr")" = 1 ] && ! grep "interrupted by signal 15" "$work/stderr" |
  grep -q run.json || fail "run.json unwritable: expected the interruption on a line of its own: $(cat "$work/stderr")"
# 4. SIGTERM to mpirun itself, which stops reading the ranks' output and passes the signal on only after its kill
# timeout: a fast history (64², tens of rows a second) fills rank 0's stdout meanwhile, and rank 0, blocked
# writing a row, lost run.json and the message to the SIGKILL that follows (3 of 3 with the timeout raised to 5 or
# 10 s, findings-recheck.md redteam6). With the timeout raised: the record and the message; with the default 1 s
# the record (written first: the message comes after the history figure, which a loaded machine may not reach
# before the SIGKILL, docs/mpi.md; seen once at load 8).
for timeout_s in 5 1; do
  OMPI_MCA_odls_base_sigkill_timeout=$timeout_s timeout $limit "$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent \
    --n 64 --approach 1:10:4000 --out "$work/mpirun$timeout_s" > "$work/stdout" 2> "$work/stderr" &
  launcher=$!
  for _ in $(seq 2400); do
    [ "$(wc -l 2>/dev/null < "$work/mpirun$timeout_s/history.csv" || echo 0)" -gt 3 ] && break
    sleep 0.05
  done
  kill -TERM "$(pgrep -P $launcher)"
  wait $launcher
  status=$?
  case="SIGTERM to mpirun, kill timeout $timeout_s s"
  [ $status != 124 ] || fail "$case: hung (timeout)"
  grep -q '"status": "interrupted"' "$work/mpirun$timeout_s/run.json" 2>/dev/null ||
    fail "$case: no run.json \"interrupted\": $(ls "$work/mpirun$timeout_s"); $(cat "$work/stderr")"
  rows=$(($(wc -l < "$work/mpirun$timeout_s/history.csv") - 1))
  grep -q "\"steps_completed\": $rows," "$work/mpirun$timeout_s/run.json" || fail "$case: steps_completed, $rows rows"
  [ "$timeout_s" = 1 ] || [ "$(grep -c "interrupted by signal 15" "$work/stderr")" = 1 ] ||
    fail "$case: the message: $(cat "$work/stderr")"
  # The case is the blocked one: mpirun stopped reading, so its stdout has fewer rows than history.csv (rank 0
  # was held on the full output, then dropped what it could not write). Not under the sanitizers, whose slower
  # rows may not fill the output within the 5 s.
  [ "$timeout_s" = 1 ] || [ "${IM_SANITIZED:-0}" = 1 ] || [ "$(grep -c '^[0-9]' "$work/stdout")" -lt "$rows" ] ||
    fail "$case: stdout holds all $rows rows: rank 0 never blocked, the case tested nothing"
done
echo "a history interrupted over ranks keeps its steps, its record says so first, one message, exit 143"
echo "cli_mpi_signal: ok"
