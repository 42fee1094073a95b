#!/usr/bin/env bash
# Nominally flat contact over 1 and 2 ranks against the serial solver (bench/bench_mpi_periodic.c),
# 512^2 and 1024^2 at p_m = 0.004 (about 10% contact), cascade on and off, one OpenMP thread per
# rank, loopback; each configuration REPEATS times (default 3), alternated.
#   bench/run_mpi_periodic.sh BUILD_DIR [REPEATS]
set -euo pipefail
build=${1:-build} repeats=${2:-3}
cmake --build "$build" --target bench_mpi_periodic >/dev/null
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_mpi_yield_when_idle=1  # waiting ranks yield the core (they share 2 cores with others)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
for n in 512 1024; do
  for ((k = 0; k < repeats; ++k)); do
    for cascade in 1 0; do
      for ranks in 1 2; do
        mpirun -n $ranks --oversubscribe "$build/bench_mpi_periodic" $n 0.004 $cascade
      done
    done
  done
done
