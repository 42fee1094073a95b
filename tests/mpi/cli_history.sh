# The start and the checks of the tests of mpi-indent's histories against indent's (sourced by
# cli_mpi_adhesion.sh and cli_mpi_history.sh after cli=PATH_TO_INDENTMAP): skipped (exit 77) in a build without
# MPI or without mpiexec; Open MPI's test settings, one thread per rank, a folder $work removed on exit, fail,
# history_differences (history_compare.sh) and refused.
"$cli" --help | grep -q mpi-indent || { echo "built without MPI: skipped"; exit 77; }
mpiexec=$(command -v mpiexec || command -v mpirun) || { echo "no mpiexec: skipped"; exit 77; }
source "$(dirname "${BASH_SOURCE[0]}")/open_mpi_env.sh"
export OMP_NUM_THREADS=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
source "$(dirname "${BASH_SOURCE[0]}")/history_compare.sh"

# refused NAME PATTERN ARGUMENTS...: mpi-indent --n 32 ARGUMENTS on 2 ranks exits with 2 and one message from
# indentmap, matching PATTERN
refused() {
  local name=$1 pattern=$2
  shift 2
  timeout 300 "$mpiexec" -n 2 --oversubscribe "$cli" mpi-indent --n 32 "$@" > /dev/null 2> "$work/$name.err"
  local status=$?
  [ $status -eq 2 ] || fail "$name: exit $status, expected 2: $(cat "$work/$name.err")"
  grep -q -- "$pattern" "$work/$name.err" || fail "$name: expected '$pattern': $(cat "$work/$name.err")"
  [ "$(grep -c '^indentmap:' "$work/$name.err")" = 1 ] || fail "$name: not one message: $(cat "$work/$name.err")"
}
