# sourced by the bench scripts (from the repository root): wait policy, MPI arguments, binary
# OpenMP's wait policy: the long spin a user is advised to start threaded runs with
# (GOMP_SPINCOUNT, docs/threads.md) unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set: `passive`
# is slow on an idle machine (several short parallel regions per step), `active` stalls on a
# busy one. MPI ranks yield while they wait.
[ -n "${OMP_WAIT_POLICY:-}" ] || export GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-10000000}
read -r -a mpi_args <<<"${GS_MPI_ARGS---mca mpi_yield_when_idle 1}"
root=$PWD
gs=$root/${GS_BUILD_DIR:-build}/gransim
bench=$root/${GS_BUILD_DIR:-build}/gransim_bench
