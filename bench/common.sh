# sourced by the bench scripts (from the repository root): wait policy, MPI arguments, binary
# OpenMP's wait policy stays the runtime default (spin a while, then sleep) unless set: `passive`
# is slow on an idle machine (several short parallel regions per step), `active` stalls on a
# busy one (docs/threads.md). MPI ranks yield while they wait.
read -r -a mpi_args <<<"${GS_MPI_ARGS---mca mpi_yield_when_idle 1}"
root=$PWD
gs=$root/${GS_BUILD_DIR:-build}/gransim
bench=$root/${GS_BUILD_DIR:-build}/gransim_bench
