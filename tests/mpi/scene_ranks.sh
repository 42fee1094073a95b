#!/usr/bin/env bash
# Ensembles over ranks (docs/mpi.md): a scene of 2 slopes x 3 seeds on 64 x 64 surfaces (a table,
# load-controlled histories, fig2/fig5/fig7) run by one process and by mpirun on 2 and 4 ranks
# writes the same files to the byte (PDFs but for their creation date, member files but for
# their seconds column); --resume under mpirun reads every member back; a member that one rank
# cannot write fails the run with that rank's message; a locked folder is refused as today; an
# interrupted run (SIGINT to mpirun) keeps its members and --resume completes it.
#   scene_ranks.sh MPIEXEC PATH_TO_INDENTMAP
# Open MPI as tests/mpi/open_mpi_env.sh sets it.
set -uo pipefail
mpiexec=$1 cli=$2
source "$(dirname "$0")/open_mpi_env.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
source "$(dirname "$0")/../lib.sh"

# One scene file and one output folder for every run (run.json and the PNGs name the scene): each
# run's folder is moved aside after it.
cat > "$work/ensemble.ini" <<INI
[scene]
name = ensemble
output = $work/out
[surfaces]
n = 64
hurst = 0.8
lambda_s = 4
slopes = 0.04, 0.08
seeds = 1:3
[punch]
shape = cone
alpha = 80
[loading]
load_star = 400
control = load
steps = 100:400:4
[solver]
tol = 1e-8
[output]
table = yes
plots = fig2, fig5, fig7
INI

run() { # run NAME COMMAND...: runs the scene, keeps its folder as NAME and its stderr as NAME.log
  local name=$1
  shift
  "$@" run "$work/ensemble.ini" 2> "$work/$name.log" > /dev/null || fail "$name: exit $?: $(cat "$work/$name.log")"
  mv "$work/out" "$work/$name"
}
# same_ranks_outputs A B: the runs kept as A and B wrote the same files (lib.sh's same_outputs).
same_ranks_outputs() { same_outputs "$work/$1" "$work/$2" || fail "$1 and $2 wrote other outputs"; }

run single "$cli"
for f in table1.csv table1.md fig2.png fig5.png fig7.png histories/member_01_3.csv table/member_00_2.csv; do
  [ -s "$work/single/$f" ] || fail "the single process wrote no $f"
done
for k in 2 4; do
  run ranks$k "$mpiexec" -n $k --oversubscribe "$cli"
  same_ranks_outputs single ranks$k
  grep -q "ensembles over $k MPI ranks" "$work/ranks$k.log" || fail "$k ranks: $(cat "$work/ranks$k.log")"
  # the stage lines count the ranks' members as solved, as a single process counts its own
  grep -q "table: 6 surfaces: 6 solved, 0 read back" "$work/ranks$k.log" || fail "$k ranks: $(cat "$work/ranks$k.log")"
  grep -q "histories: 6 steps at load_star taken from the table" "$work/ranks$k.log" ||
    fail "$k ranks: $(cat "$work/ranks$k.log")"
done
echo "1, 2 and 4 ranks: the same tables, histories and figures"

# A profile punch (an 80 degree cone as an (r, z) table beside the scene): every rank reads it (the
# ranks' member keys hold its samples, as rank 0's), the same histories on 2 ranks as in one process.
printf 'r,z\n0,0\n10,1.7632698070846498\n20,3.5265396141692996\n40,7.053079228338599\n' > "$work/tip.csv"
sed -e 's/^shape = cone/shape = profile\nprofile = tip.csv/' -e '/^alpha = /d' -e '/^table = /d' -e 's/^plots = .*/plots = fig5/' \
  -e 's/^control = load/control = displacement/' -e 's/^steps = .*/steps = 0.5, 1.5/' "$work/ensemble.ini" > "$work/profile.ini"
cp "$work/ensemble.ini" "$work/plain.ini" && cp "$work/profile.ini" "$work/ensemble.ini"
run profile_single "$cli"
run profile_ranks2 "$mpiexec" -n 2 --oversubscribe "$cli"
same_ranks_outputs profile_single profile_ranks2
grep -q "ensembles over 2 MPI ranks" "$work/profile_ranks2.log" && grep -q "histories: 6 surfaces: 6 solved, 0 read back" "$work/profile_ranks2.log" ||
  fail "a profile on 2 ranks: $(cat "$work/profile_ranks2.log")"
cp "$work/plain.ini" "$work/ensemble.ini"
echo "a profile punch: 1 and 2 ranks write the same histories"

# Contact panels (where OpenGL is at hand): the forces the ranks kept for them reach rank 0's panels
# (counted as reused from the table, as in a single process), the same panels to the byte.
sed -e 's/^table = yes/table = yes\ncontact_panels = yes/' "$work/ensemble.ini" > "$work/panels.ini"
cp "$work/ensemble.ini" "$work/plain.ini" && cp "$work/panels.ini" "$work/ensemble.ini"
if [[ ${ASAN_OPTIONS:-} == *fast_unwind_on_malloc=0* ]]; then
  # the sanitizer pass's full unwinding on every malloc (for Open MPI's suppressions) deadlocks in
  # llvmpipe's JIT (libgcc's unwinder lock taken again from LLVM's registerEHFrames)
  echo "sanitizers with full unwinding: the panels are not compared"
elif "$cli" run "$work/ensemble.ini" > /dev/null 2> "$work/panels_single.log"; then
  mv "$work/out" "$work/panels_single"
  run panels_ranks3 "$mpiexec" -n 3 --oversubscribe "$cli"
  same_ranks_outputs panels_single panels_ranks3
  grep -q "panels: 2 surfaces: 0 solved, 0 read back, 2 reused" "$work/panels_ranks3.log" ||
    fail "panels on 3 ranks: $(cat "$work/panels_ranks3.log")"
  echo "3 ranks: the same contact panels"
else
  grep -q "rendering with" "$work/panels_single.log" && fail "panels: $(cat "$work/panels_single.log")"
  echo "no OpenGL context: the panels are not compared"
  rm -rf "$work/out"
fi
cp "$work/plain.ini" "$work/ensemble.ini"

# --resume on 3 ranks over the 4 ranks' folder: every member read back, nothing solved, same files
cp -r "$work/ranks4" "$work/out"
"$mpiexec" -n 3 --oversubscribe "$cli" run --resume "$work/ensemble.ini" 2> "$work/resume.log" > /dev/null ||
  fail "--resume on 3 ranks: exit $?: $(cat "$work/resume.log")"
mv "$work/out" "$work/resume"
grep -q "table: 6 surfaces: 0 solved, 6 read back" "$work/resume.log" || fail "--resume: $(cat "$work/resume.log")"
grep -q "histories: 6 surfaces: 0 solved, 6 read back" "$work/resume.log" || fail "--resume: $(cat "$work/resume.log")"
same_ranks_outputs single resume
echo "--resume on 3 ranks: every member read back, the same files"

# A member only rank 1 solves (family 0, seed 2: member 1) cannot be written: the run fails with
# that rank's message, on 2 and on 4 ranks.
for k in 2 4; do
  mkdir -p "$work/out/table/member_00_2.csv"
  "$mpiexec" -n $k --oversubscribe "$cli" run "$work/ensemble.ini" > /dev/null 2> "$work/fail$k.log"
  status=$?
  [ $status -ne 0 ] || fail "$k ranks: a member that cannot be written, yet exit 0"
  grep -q "indentmap: rank 1: family 0, seed 2: .*member_00_2.csv" "$work/fail$k.log" ||
    fail "$k ranks: expected rank 1's message naming the member: $(cat "$work/fail$k.log")"
  [ ! -e "$work/out/table1.csv" ] || fail "$k ranks: table1.csv written after a failed member"
  rm -rf "$work/out"
done
echo "a rank's failure fails the run with its message"

# A folder another run holds: refused on rank 0, the other ranks end with it (no hang)
mkdir -p "$work/out"
exec 9> "$work/out/.lock" # this shell holds the lock, as another run would
flock 9
timeout 120 "$mpiexec" -n 2 --oversubscribe "$cli" run "$work/ensemble.ini" > /dev/null 2> "$work/locked.log" 9>&-
status=$?
exec 9>&-
[ $status -ne 0 ] && [ $status -ne 124 ] || fail "locked folder: exit $status: $(cat "$work/locked.log")"
grep -q "give this scene another \[scene\] output" "$work/locked.log" || fail "locked folder: $(cat "$work/locked.log")"
[ ! -e "$work/out/table" ] || fail "locked folder: a rank wrote members into it"
rm -rf "$work/out"
echo "a locked folder is refused"
# Interruption. On SIGINT, mpirun (Open MPI 4.1) sends the ranks SIGCONT at once, SIGTERM
# odls_base_sigkill_timeout seconds later (1 by default) and SIGKILL as long again after that:
# timed against a member stage of about a second, that races. So the test freezes both ranks once
# the first member is on disk (every rank is then past its signal handlers), sends them the SIGTERM
# mpirun would send, and thaws them: the signal surely lands in the member stage. mpirun reports the
# ranks' exit as it would after a Ctrl-C; it waits two of its timeouts before it ends after a rank's
# non-zero exit, set to 5 s so that a slow rank still reaches its check on a loaded machine.
sed -e 's/^n = 64/n = 192/' -e 's/^seeds = 1:3/seeds = 1:12/' -e 's/^steps = .*/steps = 100:400:12/' \
  "$work/ensemble.ini" > "$work/longer.ini"
OMPI_MCA_odls_base_sigkill_timeout=5 "$mpiexec" -n 2 --oversubscribe "$cli" run "$work/longer.ini" \
  > /dev/null 2> "$work/interrupted.log" &
launcher=$!
for _ in $(seq 1200); do ls "$work/out/table"/member_* >/dev/null 2>&1 && break; sleep 0.05; done
ranks=$(pgrep -P $launcher)
[ "$(echo $ranks | wc -w)" = 2 ] || fail "interrupted: the ranks under mpirun: '$ranks'"
kill -STOP $ranks
kill -TERM $ranks
kill -CONT $ranks
wait $launcher
status=$?
[ $status -ne 0 ] || fail "interrupted: exit 0: $(cat "$work/interrupted.log")"
grep -q "interrupted by signal" "$work/interrupted.log" || fail "interrupted: $(cat "$work/interrupted.log")"
! find "$work/out" -name '*.tmp.*' | grep -q . || fail "interrupted: temporary files left"
[ ! -e "$work/out/table1.csv" ] || fail "interrupted: the run went on to the table"
"$mpiexec" -n 2 --oversubscribe "$cli" run --resume "$work/longer.ini" > /dev/null 2> "$work/resumed.log" ||
  fail "--resume after the interruption: exit $?: $(cat "$work/resumed.log")"
grep -Eq "(table|histories): 24 surfaces: [0-9]+ solved, [1-9][0-9]* read back" "$work/resumed.log" ||
  fail "--resume after the interruption read nothing back: $(cat "$work/resumed.log")"
[ -s "$work/out/table1.csv" ] && [ -s "$work/out/fig7.png" ] || fail "--resume after the interruption: no table or fig7"
echo "an interrupted run keeps its members; --resume completes it"
echo "scene_ranks: ok"
