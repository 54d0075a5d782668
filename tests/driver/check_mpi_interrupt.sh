#!/bin/bash
# Ctrl-C on mpirun: Open MPI's mpirun answers SIGINT by sending every rank SIGTERM (then SIGKILL a
# few seconds later). `shard run` must stop all ranks at one step with a checkpoint on SIGTERM, and
# `--restart` on the same ranks must end where the uninterrupted run ends (same step, same peak).
# Usage: check_mpi_interrupt.sh SHARD MPIEXEC WORK
source "$(dirname "$0")/mpi_common.sh"
scene="$(dirname "$0")/../../scenes/four_point_bending_ci.toml"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive

mpi 2 "$shard" run "$scene" --out "$work/whole" > "$work/whole.log" 2>&1

# mpirun itself in the background (not through mpi(): a function's subshell would take the signal).
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$shard" run "$scene" --out "$work/cut" --checkpoint-every 1 \
  > "$work/cut.log" 2>&1 &
runner=$!
for _ in $(seq 300); do
  [ -f "$work/cut/run.checkpoint.h5" ] && break
  sleep 0.05
done
[ -f "$work/cut/run.checkpoint.h5" ] || { echo "FAIL: no checkpoint within 15 s"; cat "$work/cut.log"; exit 1; }
kill -INT "$runner"
wait "$runner" || true
grep -q "interrupted (SIGTERM) at step" "$work/cut.log" || { echo "FAIL: the ranks did not stop on mpirun's SIGTERM"; tail -5 "$work/cut.log"; exit 1; }
cut_step=$(grep -o "interrupted (SIGTERM) at step [0-9]*" "$work/cut.log" | head -1 | grep -o "[0-9]*$")

mpi 2 "$shard" run --restart "$work/cut/run.h5" > "$work/resumed.log" 2>&1
summary() { grep -o "; [0-9]* steps, t = [^,]*, [0-9]* bonds broken" "$1"; }
peak() { grep -o "peak load [^ ]* N at displacement [^ ]* m" "$1"; }
if [ "$(summary "$work/whole.log")" != "$(summary "$work/resumed.log")" ] || [ "$(peak "$work/whole.log")" != "$(peak "$work/resumed.log")" ]; then
  echo "FAIL: the resumed run ends otherwise than the uninterrupted one"
  echo "whole:   $(summary "$work/whole.log") $(peak "$work/whole.log")"
  echo "resumed: $(summary "$work/resumed.log") $(peak "$work/resumed.log")"
  exit 1
fi
echo "mpirun interrupted: both ranks stopped at step $cut_step on SIGTERM with a checkpoint; resumed on 2 ranks:$(summary "$work/resumed.log"), $(peak "$work/resumed.log"), as the uninterrupted run"
