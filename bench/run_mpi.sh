#!/usr/bin/env bash
# Strong and weak scaling of the distributed solver over 1-4 ranks on this machine (loopback,
# oversubscribed past its cores), one OpenMP thread per rank: bench/bench_mpi.c per line.
#   bench/run_mpi.sh BUILD_DIR [REPEATS]
set -euo pipefail
build=${1:-build} repeats=${2:-5}
cmake --build "$build" --target bench_mpi >/dev/null
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_mpi_yield_when_idle=1  # waiting ranks yield the core (they share 2 cores with others)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
echo "# strong scaling: 512 x 512"
for k in 1 2 3 4; do mpirun -n $k --oversubscribe "$build/bench_mpi" 512 512 "$repeats"; done
echo "# weak scaling: 256 x 256 per rank"
mpirun -n 1 --oversubscribe "$build/bench_mpi" 256 256 "$repeats"
mpirun -n 2 --oversubscribe "$build/bench_mpi" 256 512 "$repeats"
mpirun -n 3 --oversubscribe "$build/bench_mpi" 256 768 "$repeats"
mpirun -n 4 --oversubscribe "$build/bench_mpi" 512 512 "$repeats"
echo "# memory model: 1024 x 1024"
for k in 1 2 4; do mpirun -n $k --oversubscribe "$build/bench_mpi" 1024 1024 3; done
