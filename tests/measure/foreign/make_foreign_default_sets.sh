#!/usr/bin/env bash
# Foreign-truth measurement sets at the default beam's size (docs/explanation/diagnosis.md "Checked on
# foreign truth"): `shard synth` on
# tests/measure/foreign/foreign_default_beam.toml (foreign_spring_bond on an hcp lattice of
# 4.4-4.8 mm spheres, 180 x 30 x 35 mm, 20 mm/s), to be diagnosed with scenes/four_point_bending.toml.
# The sets of make_foreign_sets.sh (which makes them), sizes scaled to this beam where they have a unit.
#
#   make_foreign_default_sets.sh SHARD PLUGIN_DIR OUT WORK [WORKERS]
#
# Sets (4 specimens each, own packing seeds and noise seed):
#   reference    the foreign base model                       seeds 1001-1004
#   null         the same, another draw                       seeds 1101-1104
#   compliance   load-frame spring C = 6e-5 m/N (2/3 of the specimen's secant compliance
#                w_peak / F_max ~ 9e-5 m/N, as 2e-4 m/N is on the tiny foreign beam)   1201-1204
#   weibull      bond strength scatter, Weibull m = 2                              1301-1304
#   softening    softening ratio 1.5                                               1401-1404
#   asymmetry    normal bond spring 3x stiffer in compression                      1501-1504
#   toe          seating toe g = 2.5 mm, F_h = 15 N (outside the library; on the tiny foreign
#                beam 0.5 mm and 0.5 N, scaled by w_peak and F_max)                1601-1604
# Sensor model: 2 % specimen scatter, 0.05 N load-cell noise, 0.02 N tare sd, 1 um displacement
# steps; lab conditions recorded in metadata.toml [test]: 20 mm/s reached along a 1-cos ramp over
# 25 ms, a seating preload of 0.5 N (1 % of F_max ~ 58 N), a zero offset of 0.05 N.
set -euo pipefail
if [[ $# -lt 4 || $# -gt 5 ]]; then
  echo "usage: $0 SHARD PLUGIN_DIR OUT WORK [WORKERS]" >&2
  exit 2
fi
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
FOREIGN_SCENE=$here/foreign_default_beam.toml \
FOREIGN_LABEL="foreign default beam" \
FOREIGN_SENSOR="--scatter 0.02 --force-noise 0.05 --force-offset 0.02 --displacement-step 1e-6 --seeds 4 \
--ramp 1-cos --ramp-time 0.025 --seating-preload 0.5 --zero-offset 0.05 --workers ${5:-2}" \
FOREIGN_COMPLIANCE=6e-5 \
FOREIGN_TOE="--seating-gap 2.5e-3 --seating-half-force 15" \
  exec bash "$here/make_foreign_sets.sh" "$1" "$2" "$3" "$4"
