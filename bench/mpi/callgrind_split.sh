#!/bin/sh
# The work split of a decomposed step in instructions (valgrind's callgrind: exact, and not moved
# by the other jobs of a shared machine). Usage, from the source tree:
#   bench/mpi/callgrind_split.sh NP [particles=10000] [steps=20] >> measurements.txt
# One line per rank: its owned particles and ghosts and the inclusive instruction counts over the
# run's steps (5 warm-up + steps) of Simulation::step (the compute, the halo called from inside it
# included), the halo's two exchanges (Halo::refresh_ghosts, Halo::return_reactions) and
# DistributedSimulation::finish_step (the per-step reduction; re-partitions inside it, also given);
# exchange_Ir: the messages inside the halo's (MPI's polling while it waits included).
set -eu
NP=$1
N=${2:-10000}
S=${3:-20}
BUILD=${BUILD:-build/mpi}
# CALLGRIND_DIR: the folder of an earlier run's files (cg.PID and log) to read again instead of running.
if [ -n "${CALLGRIND_DIR:-}" ]; then
  DIR=$CALLGRIND_DIR
else
  DIR=$(mktemp -d)
  # (mpirun may report a failure at the end under valgrind: the rank lines below decide)
  OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive mpirun --allow-run-as-root --oversubscribe --bind-to none -np "$NP" \
    valgrind --tool=callgrind --callgrind-out-file="$DIR/cg.%p" "$BUILD/bench/mpi/bench_mpi" block "$N" "$S" >"$DIR/log" 2>"$DIR/err" ||
    echo "callgrind_split: mpirun exit status $? (files kept in $DIR)" >&2
fi
inclusive() {  # $1 file, $2 function name as callgrind_annotate prints it
  callgrind_annotate --inclusive=yes --threshold=100 "$1" 2>/dev/null | grep -F ":$2" | head -1 | awk '{gsub(",", "", $1); print $1}'
}
grep '^bench_mpi_rank' "$DIR/log" | while read -r _ _ rank pid owned ghosts _; do
  f="$DIR/cg.${pid#pid=}"
  step=$(inclusive "$f" 'shard::Simulation::step()')
  refresh=$(inclusive "$f" 'shard::mpi::Halo::refresh_ghosts(')
  back=$(inclusive "$f" 'shard::mpi::Halo::return_reactions(')
  exchange=$(inclusive "$f" 'shard::mpi::Halo::exchange(')
  finish=$(inclusive "$f" 'shard::mpi::DistributedSimulation::finish_step()')
  repart=$(inclusive "$f" 'shard::mpi::DistributedSimulation::repartition()')
  echo "callgrind block$N ranks=$NP $rank $owned $ghosts steps=$((S + 5)) step_Ir=${step:-0} halo_Ir=$(( ${refresh:-0} + ${back:-0} )) exchange_Ir=${exchange:-0} finish_Ir=${finish:-0} repartition_Ir=${repart:-0}"
done
[ -n "${CALLGRIND_DIR:-}" ] || rm -rf "$DIR"
