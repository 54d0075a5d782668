#!/bin/bash
# Distributed ensembles (docs/how-to/run-on-a-cluster.md): the measurement loop's runs handed out over MPI ranks
# give the numbers of the serial run. `shard synth` on the tiny beam, serially and under mpirun
# with 3 ranks (rank 0 runs the command, ranks 1-2 the simulations), must write the same
# measurement set byte for byte; `shard compare` of the model against that set under mpirun with
# 2 ranks, each run in a worker process on its rank (--isolate), must write the serial compare.json
# (NRMSE, chi-square, features). Each rank count starts from an empty work
# folder, so every run is simulated again (not read from the serial run's cache).
# Usage: check_mpi_ensemble.sh SHARD MPIEXEC WORK
source "$(dirname "$0")/mpi_common.sh"
scene="$(dirname "$0")/../../scenes/measurements/tiny_bending.toml"
model=(--scene "$scene" --seeds 3 --set stop.max_displacement=0.0006)

"$shard" synth "${model[@]}" --work "$work/serial" --out "$work/serial_set" --force-noise 0.01 > "$work/serial.log" 2>&1
mpi 3 "$shard" synth "${model[@]}" --work "$work/mpi" --out "$work/mpi_set" --force-noise 0.01 > "$work/mpi.log" 2>&1
grep -q "3 runs over 2 MPI ranks" "$work/mpi.log" || { echo "FAIL: the runs did not go to the ranks"; cat "$work/mpi.log"; exit 1; }
if ! diff -r "$work/serial_set" "$work/mpi_set"; then
  echo "FAIL: the measurement set written with 3 MPI ranks differs from the serial one"
  exit 1
fi

compare=(compare "$work/serial_set" "${model[@]}" --first-seed 1)
"$shard" "${compare[@]}" --work "$work/serial_compare" --out "$work/serial_compare_out" > "$work/serial_compare.log" 2>&1
mpi 2 "$shard" "${compare[@]}" --isolate --work "$work/mpi_compare" --out "$work/mpi_compare_out" > "$work/mpi_compare.log" 2>&1
grep -q "3 runs over 1 MPI rank" "$work/mpi_compare.log" || { echo "FAIL: compare's runs did not go to the rank"; cat "$work/mpi_compare.log"; exit 1; }
# compare.json holds the NRMSE, the chi-square and every feature and residual, to nine digits.
if ! cmp "$work/serial_compare_out/compare.json" "$work/mpi_compare_out/compare.json"; then
  echo "FAIL: compare.json over 2 ranks differs from the serial one"
  diff "$work/serial_compare_out/compare.json" "$work/mpi_compare_out/compare.json" | head -20
  exit 1
fi
echo "synth over 3 ranks: the serial measurement set byte for byte; compare over 2 ranks (--isolate): the serial compare.json, $(grep -m1 -o '"nrmse": [^,]*' "$work/mpi_compare_out/compare.json")"
