#!/bin/sh
# The strong-scaling figures and the cost model's calibration (docs/explanation/scaling.md), each command a
# one-liner that can be re-run alone. Appends every summary line to $OUT; then
#   python3 bench/mpi/cost_model.py $OUT
# prints the calibrated constants and the projection table. Run from the source tree, with a
# SHARD_WITH_MPI build in $BUILD (default build/mpi). REPS runs of each timing (best of them is
# what the model takes). WHAT: a space list of block pack seed partition pingpong frames callgrind
# (default all; callgrind: the work split of the block on 1 and 2 ranks under valgrind, a few
# minutes; frames: a frame's gather and write, which the model does not read).
set -eu
BUILD=${BUILD:-build/mpi}
OUT=${OUT:-bench/mpi/measured/$(hostname)-$(date -u +%Y%m%dT%H%M).txt}
REPS=${REPS:-3}
WHAT=${WHAT:-"block pack seed partition pingpong frames callgrind"}
SEED=scenes/four_point_bending_seed.toml
SEED_STEPS=${SEED_STEPS:-50}
B=$BUILD/bench/mpi/bench_mpi
M="mpirun --allow-run-as-root --oversubscribe --bind-to none"
export OMP_WAIT_POLICY=passive
mkdir -p "$(dirname "$OUT")"
run() { echo "# $*" >>"$OUT"; "$@" | tee -a "$OUT"; }
has() { case " $WHAT " in *" $1 "*) return 0 ;; esac; return 1; }
echo "# $(date -u +%FT%TZ) $(git rev-parse --short HEAD 2>/dev/null || true) nproc=$(nproc) load=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$OUT"
for rep in $(seq "$REPS"); do
  if has frames; then
    for n in 1 2 4; do run env OMP_NUM_THREADS=1 $M -np $n $B frames 20000 20; done
  fi
  if has block; then
    run env OMP_NUM_THREADS=1 $M -np 1 $B block 20000 300
    run env OMP_NUM_THREADS=1 $M -np 2 $B block 20000 300
    run env OMP_NUM_THREADS=1 $M -np 2 $B --barriers block 20000 300
    run env OMP_NUM_THREADS=1 $M -np 1 $B --serial block 20000 300
    run env OMP_NUM_THREADS=2 $M -np 1 $B --serial block 20000 300
  fi
  if has pack; then
    run env OMP_NUM_THREADS=1 $M -np 1 $B --serial pack 100000 100
  fi
  if has seed; then
    run env OMP_NUM_THREADS=1 $M -np 1 $B scene $SEED "$SEED_STEPS"
    run env OMP_NUM_THREADS=1 $M -np 2 $B scene $SEED "$SEED_STEPS"
    run env OMP_NUM_THREADS=1 $M -np 2 $B --barriers scene $SEED "$SEED_STEPS"
    run env OMP_NUM_THREADS=1 $M -np 1 $B --serial scene $SEED "$SEED_STEPS"
    run env OMP_NUM_THREADS=2 $M -np 1 $B --serial scene $SEED "$SEED_STEPS"
  fi
done
if has partition; then
  run env OMP_NUM_THREADS=1 $M -np 1 $B partition scene $SEED 2 4 8 16 32 64 128 256
  run env OMP_NUM_THREADS=1 $M -np 1 $B partition block 20000 2 4 8 16 32 64
  run env OMP_NUM_THREADS=1 $M -np 1 $B partition block 10000000 16 64 256
fi
if has pingpong; then
  run env OMP_NUM_THREADS=1 mpirun --allow-run-as-root --bind-to none -np 2 $B pingpong
fi
if has callgrind; then
  for np in 1 2; do
    echo "# bench/mpi/callgrind_split.sh $np 20000 20" >>"$OUT"
    BUILD=$BUILD "$(dirname "$0")/callgrind_split.sh" "$np" 20000 20 | tee -a "$OUT"
  done
fi
echo "wrote $OUT"
