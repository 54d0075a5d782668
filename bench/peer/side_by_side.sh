#!/bin/sh
# Two builds' step loops on one scene at the same time, one pinned to each of two cores, the cores
# swapped every round: on a machine shared with other jobs both face the same load, and each
# build's CPU time per bond-step compares with the other's on the same core.
#   sh bench/peer/side_by_side.sh BENCH_A BENCH_B SCENE [STEPS=400] [ROUNDS=6] [SCENE_B=SCENE]
# BENCH_A and BENCH_B are two builds' bench/kernel/bench_kernel.
set -e
a=${1:?usage: side_by_side.sh BENCH_A BENCH_B SCENE [STEPS] [ROUNDS] [SCENE_B]}
b=${2:?usage: side_by_side.sh BENCH_A BENCH_B SCENE [STEPS] [ROUNDS] [SCENE_B]}
scene=${3:?usage: side_by_side.sh BENCH_A BENCH_B SCENE [STEPS] [ROUNDS] [SCENE_B]}
steps=${4:-400}
rounds=${5:-6}
scene_b=${6:-$scene}
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
figure() { tail -n 1 | grep -o 'cpu_ns_per_bond_step=[0-9.]*'; }
r=0
while [ "$r" -lt "$rounds" ]; do
  core_a=$((r % 2))
  core_b=$((1 - core_a))
  (echo "A core $core_a $(taskset -c "$core_a" "$a" scene "$scene" "$steps" 2>&1 | figure)") &
  (echo "B core $core_b $(taskset -c "$core_b" "$b" scene "$scene_b" "$steps" 2>&1 | figure)") &
  wait
  r=$((r + 1))
done
