#!/usr/bin/env bash
# Seven measurement sets on the default beam (scenes/four_point_bending.toml: 180 x 30 x 35 mm,
# 865 spheres of 5.0-6.5 mm), for the cost of the contrast diagnosis at the default resolution
# (docs/explanation/diagnosis.md "Contrasts", Cost). Made by Shard's own model on other
# packing seeds (not a foreign form: the foreign_spring_bond stiffnesses are tuned to the tiny
# beam), with the lab's test conditions of the foreign sets scaled to this beam: 20 mm/s reached
# along a 1-cos ramp over 25 ms, a 0.5 N seating preload (1 % of F_max ~ 49 N), a 0.05 N zero
# offset; 4 specimens per set, 2 % specimen scatter, 0.05 N load-cell noise, 0.02 N tare sd.
#
#   make_default_beam_sets.sh SHARD OUT WORK
#
# Sets: reference (seeds 2001-2004), null (2101-), compliance 3e-5 m/N (a third of the specimen's
# secant compliance w_peak / F_max ~ 1e-4 m/N), weibull m = 4, softening ratio 1.5, compression
# ratio 3, toe (seating gap 1 mm, half closure at 5 N: outside the library).
set -euo pipefail
if [[ $# -ne 3 ]]; then
  echo "usage: $0 SHARD OUT WORK" >&2
  exit 2
fi
shard=$1 out=$2 work=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
scene=$here/../../scenes/four_point_bending.toml
mkdir -p "$out" "$work"

sensor=(--scatter 0.02 --force-noise 0.05 --force-offset 0.02 --displacement-step 1e-6 --seeds 4 --rates 0.02
        --ramp 1-cos --ramp-time 0.025 --seating-preload 0.5 --zero-offset 0.05)

synth() {  # name first_seed noise_seed [extra synth options...]
  local name=$1 first=$2 noise=$3
  shift 3
  rm -rf "${out:?}/$name"
  "$shard" synth --scene "$scene" --work "$work" --out "$out/$name" --name "default beam $name" \
    --first-seed "$first" --noise-seed "$noise" "${sensor[@]}" "$@"
}

synth reference 2001 11
synth null 2101 12
synth compliance 2201 13 --machine-compliance 3e-5
synth weibull 2301 14 --set bond.strength_weibull_modulus=4
synth softening 2401 15 --set bond.softening_ratio=1.5
synth asymmetry 2501 16 --set bond.compression_stiffness_ratio=3
synth toe 2601 17 --seating-gap 1e-3 --seating-half-force 5
