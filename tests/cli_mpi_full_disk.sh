#!/usr/bin/env bash
# mpi-indent's MPI-IO fields onto a full disk (MPI builds; skipped, exit 77, elsewhere, or where no private mount
# namespace can be made): a 64 KiB tmpfs (in a private mount namespace, as cli_full_disk.sh) cannot hold a 128^2
# force.npy. The run must fail naming the file and the rows not written, exit non-zero, and leave neither the
# field nor a temporary file (findings-recheck.md, redteam6 M2: Open MPI's ompio printed its pwritev error,
# returned success, and the run exited 0 with force.npy and gap.npy full of holes).
#   cli_mpi_full_disk.sh PATH_TO_INDENTMAP
set -uo pipefail
cli=$1
"$cli" --help | grep -q mpi-indent || { echo "built without MPI: skipped"; exit 77; }
mpiexec=$(command -v mpiexec || command -v mpirun) || { echo "no mpiexec: skipped"; exit 77; }
if [ -z "${IM_PRIVATE_MOUNTS:-}" ]; then
  unshare -m true 2>/dev/null || { echo "SKIPPED: no private mount namespace (unshare -m)"; exit 77; }
  IM_PRIVATE_MOUNTS=1 exec unshare -m bash "$0" "$@"
fi
source "$(dirname "$0")/mpi/open_mpi_env.sh"
export OMP_NUM_THREADS=1 IM_FFTW_WISDOM=
work=$(mktemp -d)
trap 'umount "$work/tiny" 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
mkdir "$work/tiny"
mount -t tmpfs -o size=64k tmpfs "$work/tiny" || { echo "SKIPPED: cannot mount a tmpfs"; exit 77; }

for k in 2 3 4; do
  "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --n 128 --approach 3 --out "$work/tiny/out$k" \
    > "$work/stdout" 2> "$work/stderr"
  status=$?
  [ $status -ne 0 ] || fail "$k ranks: exit 0 onto a full disk: $(ls -la "$work/tiny/out$k")"
  grep -q "force.npy: MPI-IO wrote [0-9]* whole rows of \[0, [0-9]*) into .*: expected all" "$work/stderr" ||
    fail "$k ranks: the message: $(cat "$work/stderr")"
  [ ! -e "$work/tiny/out$k/force.npy" ] || fail "$k ranks: force.npy left on a full disk"
  ! find "$work/tiny" -name '*.tmp.*' | grep -q . || fail "$k ranks: temporary files left: $(ls -a "$work/tiny/out$k")"
  rm -rf "$work/tiny/out$k"
done
echo "a full disk under MPI-IO's fields fails the run, naming the file"
echo "cli_mpi_full_disk: ok"
