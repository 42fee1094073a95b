#!/usr/bin/env bash
# Runs tests/mpi/mpi_solver.c (or another PROGRAM of tests/mpi/ that prints its loads so) with 1, 2, 3
# and 4 ranks of one thread and 2 ranks of 2 OpenMP threads (hybrid; each run compares with the serial
# solver), or the RANKS given (N, or Nx2 for N ranks of 2 threads), then checks that every run gave the
# same loads to the bit and the same contact counts (the first seven fields of each line).
#   mpi_solver.sh MPIEXEC PROGRAM [RANKS...]
# Open MPI as tests/mpi/open_mpi_env.sh sets it.
set -euo pipefail
mpiexec=$1 program=$2
shift 2
runs=("$@")
[ $# -gt 0 ] || runs=(1 2 3 4 2x2)
source "$(dirname "$0")/open_mpi_env.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for ranks in "${runs[@]}"; do
  threads=1
  [ "$ranks" = 2x2 ] && threads=2
  echo "== ${ranks%x2} rank(s), $threads thread(s) each"
  OMP_NUM_THREADS=$threads "$mpiexec" -n "${ranks%x2}" --oversubscribe -x OMP_NUM_THREADS "$program" "$work" |
    tee "$work/out_$ranks"
  # the loads and map totals (hexadecimal) and contact counts, without the iteration counts
  cut -d' ' -f1-7 "$work/out_$ranks" > "$work/loads_$ranks"
  [ -s "$work/loads_$ranks" ] || { echo "no output from $ranks rank(s)" >&2; exit 1; }
done
for ranks in "${runs[@]:1}"; do
  if ! cmp -s "$work/loads_${runs[0]}" "$work/loads_$ranks"; then
    echo "FAILED: $ranks ranks give other loads than ${runs[0]}:" >&2
    diff "$work/loads_${runs[0]}" "$work/loads_$ranks" >&2 || true
    exit 1
  fi
done
echo "loads identical to the bit for ranks ${runs[*]}"
