#!/usr/bin/env bash
# Foreign-truth measurement sets at the lab's scale: `shard synth` on
# tests/measure/foreign/foreign_lab_beam.toml (foreign_spring_bond on an hcp lattice of 3.7-4.1 mm
# spheres, ~3,700 per beam, 180 x 30 x 35 mm, unstable fracture), to be diagnosed with
# scenes/four_point_bending.toml and scenes/measurements/effects.toml (study_foreign_lab.sh).
# Every library effect is hidden in its own set in a form of its own (not the library's code).
#
#   make_foreign_lab_sets.sh SHARD PLUGIN_DIR OUT WORK [WORKERS]
#     SHARD       the shard binary
#     PLUGIN_DIR  folder holding shard_foreign_spring_bond.so (<build>/tests/measure/foreign/plugins)
#     OUT         folder for the measurement sets (one sub-folder each)
#     WORK        run cache of the synth runs
#     WORKERS     synth's worker processes (default 1)
# FOREIGN_DRAW=k (default 0) moves every packing seed by 10000 k and every noise seed by 100 k:
# another draw of the same sets (other specimens, as a lab tests new ones for every batch).
# FOREIGN_SETS="name ..." makes only those sets (default: all), so two processes can share a draw.
#
# Each set's truth is written to its metadata.toml ([test] notes = "truth: ..."), library names
# or "none" or "outside"; study_foreign_lab.sh reads it from there. Sets of 4 specimens at
# 20 mm/s (rates: 4 at 20 and 4 at 100 mm/s):
#   reference      the foreign base model
#   null           the same, other specimens                                 truth none
#   rates_null     the same at 20 and 100 mm/s (a rate effect must not be named)  none
#   compliance     load frame d = C F + H F^(2/3): column C = 3e-5 m/N, Hertzian roller seats
#                  H = 1.15e-4 m/N^(2/3) (3.4 mm at 58 N; foreign_frame.py)       machine_compliance
#   weibull        bond strength scatter, Weibull m = 2 (median 1)                 weibull_strength
#   softening      parabolic softening past the peak load ratio, 1.5               bond_softening
#   asymmetry      normal bond spring 3x stiffer in compression                    compression_asymmetry
#   rates          subcritical damage c^16 / 2 ms (Charles' law) at 20 and 100 mm/s:
#                  slower is weaker, the stiffness unchanged                       bond_viscosity
#   friction_high  roller friction 1.0 against the grains' 0.5                     support_friction
#   friction_none  frictionless support rollers, the pins as the reference's (a lab's free
#                  rollers; with all four frictionless the beam slides off its supports)  support_friction
#   self_weight    gravity 2 g (19.62 m/s^2, a beam twice as heavy in its weight),
#                  settled on the rollers for 0.2 s before the pins move             self_weight
#   cohesion       a failed bond pulls with 0.5 N (0.32 F_n,c) until 1 mm apart    contact_cohesion
#   toe            seating toe g = 2.5 mm, F_h = 15 N (synth)                      outside
#   both           the compliance frame and softening 1.5 at once                  machine_compliance, bond_softening
# Sensor model for all: 2 % specimen scatter, 0.05 N load-cell noise, 0.02 N per-specimen zero
# error (tare sd), 1 um displacement steps; lab conditions recorded in metadata.toml [test]: the
# pins reach their rate along a 1-cos ramp over 25 ms, each curve starts at a 0.5 N seating
# preload, the load cell reads 0.05 N at zero load, the grains are 3.9 mm across.
set -euo pipefail
if [[ $# -lt 4 || $# -gt 5 ]]; then
  echo "usage: $0 SHARD PLUGIN_DIR OUT WORK [WORKERS]" >&2
  exit 2
fi
shard=$1 plugins=$2 out=$3 work=$4 workers=${5:-1}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
scene=$here/foreign_lab_beam.toml
if [[ ! -f $plugins/shard_foreign_spring_bond.so ]]; then
  echo "$0: $plugins/shard_foreign_spring_bond.so not found. Fix: build the target foreign_spring_bond" \
       "and pass <build>/tests/measure/foreign/plugins" >&2
  exit 2
fi
mkdir -p "$out" "$work"

step=1e-6
# The lab reports its grain size ([test] grain_size): the lattice's 3.7-4.1 mm spheres, 3.9 mm mean.
sensor=(--scatter 0.02 --force-noise 0.05 --force-offset 0.02 --displacement-step "$step" --seeds 4
        --ramp 1-cos --ramp-time 0.025 --seating-preload 0.5 --zero-offset 0.05 --grain-size 3.9e-3
        --workers "$workers")
frame=(3e-5 1.15e-4)   # foreign_frame.py's C [m/N] and H [m/N^(2/3)]
draw=${FOREIGN_DRAW:-0}

wanted() { [[ -z ${FOREIGN_SETS:-} || " $FOREIGN_SETS " == *" $1 "* ]]; }
synth() {  # name first_seed noise_seed truth [extra synth options...]
  local name=$1 first=$(( $2 + 10000 * draw )) noise=$(( $3 + 100 * draw )) truth=$4
  shift 4
  wanted "$name" || return 0
  rm -rf "${out:?}/$name"
  echo "$(date -u +%T) $name"
  "$shard" --plugin-dir "$plugins" synth --scene "$scene" --work "$work" --out "$out/$name" \
    --name "foreign lab beam $name" --notes "truth: $truth" --first-seed "$first" --noise-seed "$noise" \
    "${sensor[@]}" "$@"
}

synth reference 1001 1 reference
synth null 1101 2 none
synth compliance 1201 3 machine_compliance
! wanted compliance || python3 "$here/foreign_frame.py" "$out/compliance" "${frame[@]}" "$step"
synth weibull 1301 4 weibull_strength --set bond.weibull_modulus=2
synth softening 1401 5 bond_softening --set bond.softening_ratio=1.5
synth asymmetry 1501 6 compression_asymmetry --set bond.compression_ratio=3
synth toe 1601 7 outside --seating-gap 2.5e-3 --seating-half-force 15
synth both 1701 8 machine_compliance,bond_softening --set bond.softening_ratio=1.5
! wanted both || python3 "$here/foreign_frame.py" "$out/both" "${frame[@]}" "$step"
synth friction_high 1801 9 support_friction --set material_pair.grain.roller.friction=1.0
synth friction_none 1901 10 support_friction --set material_pair.grain.roller.friction=0 \
  --set wall.pin_left.material=grain --set wall.pin_right.material=grain
synth self_weight 2001 11 self_weight --set 'simulation.gravity=[0.0, 0.0, -19.62]' --set simulation.settle_time=0.2 --set simulation.settle_damping=0.7
synth cohesion 2201 13 contact_cohesion --set bond.cohesion_force=0.5 --set bond.cohesion_range=1e-3
synth rates_null 2301 14 none --rates 0.02,0.1
synth rates 2101 12 bond_viscosity --rates 0.02,0.1 --set bond.fatigue_time=2e-3 --set bond.fatigue_exponent=16
