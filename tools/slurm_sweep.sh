#!/usr/bin/env bash
# A gransim sweep as one Slurm job: every task is an MPI rank; rank 0 hands out the runs
# (control value × replica) one at a time, every rank runs them as `gransim run` child
# processes, each with OMP_NUM_THREADS = --cpus-per-task force-loop threads. The files are the
# same as those of a serial sweep (docs/cluster.md).
#
#   sbatch tools/slurm_sweep.sh scenes/paper_negative_g.toml \
#       --param drive.g_p=2,4,6,8,12,16 --replicas 4 --out runs/gp_sweep
#
# Everything after the script name is passed to `gransim sweep`. Resubmitting the same command
# continues the sweep: completed runs are kept, unfinished ones (time limit, node failure) are
# redone from the start (this script passes --force for that). Override the resources on the
# sbatch command line (sbatch --nodes=4 --ntasks-per-node=16 …) rather than editing them here.
#
# Environment: GRANSIM (default $SLURM_SUBMIT_DIR/build/gransim), GS_LAUNCHER=srun (default;
# needs Slurm's PMIx or PMI2 plugin: see `srun --mpi=list`) or mpirun (Open MPI's own launcher,
# which reads the allocation from Slurm), GS_SRUN_MPI (default pmix).
#
#SBATCH --job-name=gransim-sweep
#SBATCH --nodes=2
#SBATCH --ntasks-per-node=8
#SBATCH --cpus-per-task=4
#SBATCH --time=24:00:00
#SBATCH --output=gransim-sweep-%j.out
# SIGTERM to every task 5 minutes before the time limit: the running runs stop cleanly and
# write their state, the sweep exits with 4 and the resubmitted job continues it
#SBATCH --signal=TERM@300
# site specific, e.g.:
##SBATCH --partition=compute
##SBATCH --account=myproject
set -euo pipefail

# the MPI the binary was built with (Debian's Open MPI here; on a cluster, build gransim with
# the site's MPI module loaded and load the same module at run time), e.g.:
# module load gcc openmpi

if [ $# -lt 1 ]; then
  echo "usage: sbatch tools/slurm_sweep.sh SCENE --param KEY=V1,V2,... [sweep options]" >&2
  exit 2
fi
cd "${SLURM_SUBMIT_DIR:-.}"
gransim=${GRANSIM:-$PWD/build/gransim}
if [ ! -x "$gransim" ]; then
  echo "slurm_sweep: $gransim not found (build it first, or set GRANSIM)" >&2
  exit 2
fi

# threads of each run's force loop: the cores Slurm gives each task
export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}
export OMP_PROC_BIND=${OMP_PROC_BIND:-close}
export OMP_PLACES=${OMP_PLACES:-cores}
# srun does not pass --cpus-per-task on to the steps by itself since Slurm 22.05
export SRUN_CPUS_PER_TASK=${SLURM_CPUS_PER_TASK:-1}

echo "slurm_sweep: job ${SLURM_JOB_ID:-?}, ${SLURM_NTASKS:-1} ranks on ${SLURM_JOB_NUM_NODES:-1}" \
  "node(s), $OMP_NUM_THREADS thread(s) per run: $gransim sweep $*"
case "${GS_LAUNCHER:-srun}" in
  srun)
    srun --mpi="${GS_SRUN_MPI:-pmix}" --kill-on-bad-exit=1 "$gransim" sweep "$@" --force
    ;;
  mpirun)
    mpirun -np "${SLURM_NTASKS:-1}" --map-by "slot:PE=${OMP_NUM_THREADS}" \
      "$gransim" sweep "$@" --force
    ;;
  *)
    echo "slurm_sweep: GS_LAUNCHER must be srun or mpirun" >&2
    exit 2
    ;;
esac
