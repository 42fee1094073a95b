#!/usr/bin/env bash
# mpi-indent's MPI-IO fields onto a full disk (MPI builds; skipped, exit 77, elsewhere, or where no private mount
# namespace can be made): a tmpfs (in a private mount namespace, as cli_full_disk.sh) of 64 KiB, of three quarters
# of a 128^2 force.npy (rank 0's block fits, a later rank's does not), or full before the file (the header). The
# run must fail naming the file and the rows not written, exit non-zero, and leave neither the
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

# The message of a short or failed write by any rank (rank k > 0's prefixed "rank k: "), in its two forms: Open
# MPI's short count, or its error return.
short_write='force.npy: MPI-IO (wrote [0-9]* whole rows of \[[0-9]*, [0-9]*\) into .*: expected all|write of .* failed)'
# Or of rank 0's header, when the other ranks' rows filled the disk first (seen on 4 ranks in 64 KiB, 1 run in 6).
short_header='force.npy: MPI-IO (wrote [0-9]* of the header.s [0-9]* bytes into .*: expected all|write of the header .* failed)'

# A run into a tmpfs of SIZE on K ranks must fail naming force.npy and leave neither it nor a temporary file.
expect_refused() { # CASE K SIZE PATTERN
  local case=$1 k=$2 size=$3 pattern=$4 out="$work/tiny/out$2"
  mount -t tmpfs -o "size=$size" tmpfs "$work/tiny" || { echo "SKIPPED: cannot mount a tmpfs"; exit 77; }
  [ -z "${fill:-}" ] || head -c "$fill" /dev/zero > "$work/tiny/filler" 2>/dev/null
  "$mpiexec" -n $k --oversubscribe "$cli" mpi-indent --n 128 --approach 3 --out "$out" \
    > "$work/stdout" 2> "$work/stderr"
  local status=$?
  [ $status -ne 0 ] || fail "$case, $k ranks: exit 0 onto a full disk: $(ls -la "$out")"
  grep -Eq "$pattern" "$work/stderr" || fail "$case, $k ranks: the message: $(cat "$work/stderr")"
  [ ! -e "$out/force.npy" ] || fail "$case, $k ranks: force.npy left on a full disk"
  ! find "$work/tiny" -name '*.tmp.*' | grep -q . || fail "$case, $k ranks: temporary files left: $(ls -a "$out")"
  umount "$work/tiny"
}

# 1. 64 KiB for a 128^2 field of 131200 bytes: rank 0's block does not fit on 2 ranks; on 3 and 4 it may, and a
# later rank's write comes short (any rank's message is taken).
for k in 2 3 4; do expect_refused "64 KiB" $k 64k "$short_write|$short_header"; done

# 2. Three quarters of the file on 4 ranks: rank 0's block (a quarter and the header) fits, a later rank's write
# comes short (whichever writes last: the ranks write at once).
bytes=$((128 + 128 * 128 * 8))
expect_refused "3/4 of the file" 4 "$((bytes * 3 / 4 / 4096 * 4096))" "$short_write|$short_header"

# 3. A disk full before the file: rank 0's header is not written (Open MPI's short count of the header).
fill=$((64 * 1024)) expect_refused "full before the file" 2 64k "$short_header"
echo "a full disk under MPI-IO's fields fails the run, naming the file"
echo "cli_mpi_full_disk: ok"
