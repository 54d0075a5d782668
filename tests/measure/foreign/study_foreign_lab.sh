#!/usr/bin/env bash
# The contrast diagnosis judged on the lab-scale foreign truth, over draws: for each draw k the
# sets of make_foreign_lab_sets.sh (FOREIGN_DRAW=k) in DATA/draw_k/sets are diagnosed against
# their reference with Shard's default beam and effect library, then foreign_confusion.py prints
# truth x verdict over the draws with the wrong names counted. Before each diagnosis, the size of
# every set's difference from the reference at 20 mm/s (`shard compare SET --sim reference's
# curves`): peak force, peak displacement and stiffness in % and in units of their uncertainty.
# A set whose specimens scatter beyond the others' at p 0.01 carries its own scatter
# (--own-scatter 0.01): the foreign cohesion set does (its ductility), and pooled it would widen
# every other set's noise.
#
#   study_foreign_lab.sh SHARD DATA DRAW...
#     SHARD  the shard binary
#     DATA   folder of the draws (DATA/draw_k/sets made by make_foreign_lab_sets.sh); each
#            diagnosis goes to DATA/draw_k/diag, and the two-rate sets' (rates_null and rates at
#            20 and 100 mm/s against the reference) to DATA/draw_k/diag_rates (kept: a draw
#            already diagnosed is not run again), the model's run cache to DATA/model (shared by
#            the draws)
#     DRAW   draw numbers, e.g. 0 1 2 3
#   STUDY_MODEL (environment) the model the sets are diagnosed with:
#     random      (default) scenes/four_point_bending.toml as it is, a random packing
#     flat_zones  the same beam filled with conform_surface = true (faces flat to the grain where
#                 the rollers bear) and 10 mm unbreakable zones under the four rollers
#                 (docs/explanation/foreign-truth.md, "With flat faces where the fixture bears");
#                 its diagnoses go to draw_k/diag_flat_zones and draw_k/diag_rates_flat_zones, its
#                 run cache to DATA/model_flat_zones
set -euo pipefail
if [[ $# -lt 3 ]]; then
  echo "usage: $0 SHARD DATA DRAW..." >&2
  exit 2
fi
shard=$1 data=$2
shift 2
model=${STUDY_MODEL:-random}
case $model in
  random) model_args=() suffix="" ;;
  flat_zones)
    model_args=(--set generator.conform_surface=true)
    for roller in support_left support_right pin_left pin_right; do
      model_args+=(--set "wall.$roller.unbreakable_zone=0.010")
    done
    suffix=_flat_zones
    ;;
  *) echo "$0: STUDY_MODEL=$model is not a model of this study. Fix: STUDY_MODEL=random or flat_zones" >&2; exit 2 ;;
esac
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/../../.." && pwd)
# shellcheck source=compare_features.sh
source "$here/compare_features.sh"

# The sets of a draw that synth finished (a set still being made has no specimens.csv yet).
complete_sets() {
  local set
  for set in "$1"/sets/*; do
    if [[ -f $set/specimens.csv ]]; then echo "$set"; else echo "draw $(basename "$1"): $(basename "$set") not finished, left out" >&2; fi
  done
}

contrasts() {  # DRAW_FOLDER: each set against the reference, at 0.02 m/s
  local draw=$1 set json row
  printf '| set | peak force | peak displacement | stiffness |\n|---|---|---|---|\n'
  for set in $(complete_sets "$draw"); do
    [[ $(basename "$set") == reference ]] && continue
    json=$draw/contrast/$(basename "$set")/compare.json
    "$shard" compare "$set" --sim "$draw"/sets/reference/curves/*.csv --rate 0.02 --out "$(dirname "$json")" \
      > /dev/null 2>&1 || { echo "| $(basename "$set") | compare failed | | |"; continue; }
    row="| $(basename "$set") |"
    for f in peak_force peak_displacement stiffness; do
      row+=$(awk -v m="$(feature $f measured "$json")" -v s="$(feature $f simulated "$json")" \
        -v z="$(feature $f score "$json")" 'BEGIN { printf " %+.1f %% (%+.1f u) |", 100 * (m - s) / s, -z }')
    done
    echo "$row"
  done
}

# diagnose DRAW_FOLDER OUT SET...: the sets against the draw's reference with the default beam.
diagnose() {
  local draw=$1 out=$2 start
  shift 2
  [[ -f $out/diagnose.json ]] && return 0
  start=$(date +%s)
  "$shard" diagnose "$draw/sets/reference" "$@" --reference reference --scene "$source_dir/scenes/four_point_bending.toml" \
    --effects "$source_dir/scenes/measurements/effects.toml" --work "$data/model$suffix" "${model_args[@]}" \
    --param bond.youngs_modulus --param bond.critical_stress --own-scatter 0.01 --workers 2 --out "$out" > "$out.log" 2>&1 ||
    { tail -20 "$out.log"; echo "$0: diagnose of $out failed (log: $out.log)" >&2; exit 1; }
  echo "$(basename "$draw") $(basename "$out"): diagnose $(( $(date +%s) - start )) s wall"
}

# The sets of one rate (every finished set but the reference and the two-rate ones).
one_rate_sets() {
  local set
  for set in $(complete_sets "$1" 2>/dev/null); do
    case $(basename "$set") in reference | rates | rates_null) ;; *) echo "$set" ;; esac
  done
}

folders=()
for k in "$@"; do
  draw=$data/draw_$k
  [[ -f $draw/sets/reference/metadata.toml ]] ||
    { echo "$0: $draw/sets/reference not found. Fix: FOREIGN_DRAW=$k bash $here/make_foreign_lab_sets.sh ... $draw/sets ..." >&2; exit 2; }
  echo "draw $k: each set against the reference"
  contrasts "$draw"
  # shellcheck disable=SC2046  # one folder per word
  diagnose "$draw" "$draw/diag$suffix" $(one_rate_sets "$draw")
  if [[ -f $draw/sets/rates/specimens.csv && -f $draw/sets/rates_null/specimens.csv ]]; then
    diagnose "$draw" "$draw/diag_rates$suffix" "$draw/sets/rates_null" "$draw/sets/rates"
  fi
  folders+=("$draw")
done
python3 "$here/foreign_confusion.py" --model "$model" "${folders[@]}"
