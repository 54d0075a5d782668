# Sourced by the MPI shell tests (their usage: SCRIPT SHARD MPIEXEC WORK): the three arguments, a
# fresh WORK folder, and mpi N ARGS... for mpirun on N oversubscribed ranks.
set -euo pipefail
shard=$1
mpiexec=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
mpi() { "$mpiexec" --allow-run-as-root --oversubscribe -np "$@"; }
