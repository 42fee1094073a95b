# Open MPI's settings for the tests that run mpirun (sourced): loopback only, oversubscribed (more ranks
# than cores), allowed as root (CI runs as root).
export OMPI_MCA_btl=self,vader                        # shared memory and self: no network needed
export OMPI_MCA_btl_vader_single_copy_mechanism=none # containers forbid cross-process memory access
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_mpi_yield_when_idle=1                 # waiting ranks yield the core (oversubscribed)
export OMPI_MCA_oob_tcp_if_include=lo
# When a rank exits with an error, mpirun signals the ranks left and waits odls_base_sigkill_timeout
# (1 s) twice before it returns, whether or not any rank is left; with 0 it sends SIGKILL right after
# SIGTERM. The tests' failing runs (refused input, ranks that differ) then take 0.5 s instead of
# 2.5 s, with the same exit status and messages. The sanitizer build keeps the wait (CMakeLists.txt
# sets 1 there): a rank may still be in LeakSanitizer's check at exit when the first one fails.
export OMPI_MCA_odls_base_sigkill_timeout=${OMPI_MCA_odls_base_sigkill_timeout:-0}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
