#!/usr/bin/env bash
# Runs tests/mpi/mpi_parity.c (every solve kind over ranks against the serial solver) with 1, 2, 3 and 4
# ranks of one thread and 2 ranks of 2 OpenMP threads, then requires every run's lines (loads, approaches,
# contact counts, iterations) to be the same bytes as one rank's.
#   mpi_parity.sh MPIEXEC PROGRAM [SIDE]
# Open MPI as tests/mpi/open_mpi_env.sh sets it.
set -euo pipefail
mpiexec=$1 program=$2 side=${3:-64}
source "$(dirname "$0")/open_mpi_env.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for ranks in 1 2 3 4 2x2; do
  threads=1
  [ "$ranks" = 2x2 ] && threads=2
  echo "== ${ranks%x2} rank(s), $threads thread(s) each"
  OMP_NUM_THREADS=$threads "$mpiexec" -n "${ranks%x2}" --oversubscribe -x OMP_NUM_THREADS "$program" "$side" |
    tee "$work/out_$ranks"
  [ -s "$work/out_$ranks" ] || { echo "no output from $ranks rank(s)" >&2; exit 1; }
done
for ranks in 2 3 4 2x2; do
  if ! cmp -s "$work/out_1" "$work/out_$ranks"; then
    echo "FAILED: $ranks ranks give other results than 1 rank:" >&2
    diff "$work/out_1" "$work/out_$ranks" >&2 || true
    exit 1
  fi
done
echo "every solve kind: the serial iterations, and the same bits for 1, 2, 3 and 4 ranks and 2 ranks of 2 threads"
