#!/usr/bin/env bash
# Foreign-truth measurement sets (docs/explanation/diagnosis.md "Foreign truth"):
# `shard synth` on tests/measure/foreign/foreign_beam.toml, a base model of another form than
# Shard's (foreign_spring_bond, linear_spring contacts, a finer packing), 4 specimens per set.
#
#   make_foreign_sets.sh SHARD PLUGIN_DIR OUT WORK
#     SHARD       the shard binary
#     PLUGIN_DIR  folder holding shard_foreign_spring_bond.so (<build>/tests/measure/foreign/plugins)
#     OUT         folder for the measurement sets (one sub-folder each)
#     WORK        run cache of the synth runs
#
# Sets (each its own 4 specimens: own packing seeds and sensor-noise seed, as a lab tests new
# specimens for every batch):
#   reference    the foreign base model                       seeds 1001-1004
#   null         the same, another draw                       seeds 1101-1104
#   compliance   load-frame spring C = 2e-4 m/N (library: machine_compliance)   1201-1204
#   weibull      bond strength scatter, Weibull m = 2 (library: weibull_strength) 1301-1304
#   softening    softening ratio 1.5 (library: bond_softening)                1401-1404
#   asymmetry    normal bond spring 3x stiffer in compression (library: compression_asymmetry) 1501-1504
#   toe          seating toe g = 0.5 mm, F_h = 0.5 N (outside the library)   1601-1604
#   both         compliance and softening at once (the sizes above; two effects hidden) 1701-1704
# Sensor model for all: 2 % specimen scatter, 0.01 N load-cell noise, 0.005 N tare sd, 1 um
# displacement steps. Lab conditions for all, recorded in metadata.toml [test]: the pins reach
# 0.02 m/s along a 1-cos ramp over 25 ms (20 mm/s in 25 ms, 0.25 mm of travel); each curve starts
# at a seating preload of 0.1 N (t = 0, d = 0 there); the load cell reads 0.02 N at zero load.
# Another beam (make_foreign_default_sets.sh) changes what has a unit through the environment:
# FOREIGN_SCENE, FOREIGN_LABEL, FOREIGN_SENSOR (the sensor and lab options), FOREIGN_COMPLIANCE [m/N],
# FOREIGN_TOE (the toe's synth options). FOREIGN_DRAW=k (default 0) moves every packing seed by
# 10000 k and every noise seed by 100 k: another draw of the same sets (docs/explanation/diagnosis.md,
# "Other draws of the foreign sets").
set -euo pipefail
if [[ $# -ne 4 ]]; then
  echo "usage: $0 SHARD PLUGIN_DIR OUT WORK" >&2
  exit 2
fi
shard=$1 plugins=$2 out=$3 work=$4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
scene=${FOREIGN_SCENE:-$here/foreign_beam.toml}
label=${FOREIGN_LABEL:-foreign}
if [[ ! -f $plugins/shard_foreign_spring_bond.so ]]; then
  echo "$0: $plugins/shard_foreign_spring_bond.so not found. Fix: build the target foreign_spring_bond" \
       "and pass <build>/tests/measure/foreign/plugins" >&2
  exit 2
fi
mkdir -p "$out" "$work"

read -r -a sensor <<<"${FOREIGN_SENSOR:---scatter 0.02 --force-noise 0.01 --force-offset 0.005 --displacement-step 1e-6 --seeds 4 --ramp 1-cos --ramp-time 0.025 --seating-preload 0.1 --zero-offset 0.02}"
read -r -a toe <<<"${FOREIGN_TOE:---seating-gap 5e-4 --seating-half-force 0.5}"

draw=${FOREIGN_DRAW:-0}
synth() {  # name first_seed noise_seed [extra synth options...]
  local name=$1 first=$(( $2 + 10000 * draw )) noise=$(( $3 + 100 * draw ))
  shift 3
  rm -rf "${out:?}/$name"
  "$shard" --plugin-dir "$plugins" synth --scene "$scene" --work "$work" --out "$out/$name" \
    --name "$label $name" --first-seed "$first" --noise-seed "$noise" "${sensor[@]}" "$@"
}

synth reference 1001 1
synth null 1101 2
synth compliance 1201 3 --machine-compliance "${FOREIGN_COMPLIANCE:-2e-4}"
synth weibull 1301 4 --set bond.weibull_modulus=2
synth softening 1401 5 --set bond.softening_ratio=1.5
synth asymmetry 1501 6 --set bond.compression_ratio=3
synth toe 1601 7 "${toe[@]}"
synth both 1701 8 --machine-compliance "${FOREIGN_COMPLIANCE:-2e-4}" --set bond.softening_ratio=1.5
