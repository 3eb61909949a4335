# sourced by the bench scripts (from the repository root): wait policy, MPI arguments, binary
# a busy machine: OpenMP threads and MPI ranks that spin while waiting are descheduled and stall
# the others (30× slower with 2 threads at load 6 on 2 cores); so sleep/yield unless told otherwise
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
read -r -a mpi_args <<<"${GS_MPI_ARGS---mca mpi_yield_when_idle 1}"
root=$PWD
gs=$root/${GS_BUILD_DIR:-build}/gransim
