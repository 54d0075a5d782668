#!/usr/bin/env bash
# test_foreign_sets (label slow): makes the foreign-truth sets (make_foreign_sets.sh) and checks
#  1. every set is a measurement folder `shard compare` reads against the foreign scene (its span
#     and pin distance pass the geometry check);
#  2. every set but the reference differs from null beyond noise: |score| > 3 in peak force, peak
#     displacement or stiffness, where score = (null - set) / sqrt(u_set^2 + u_null^2) from
#     `shard compare SET --sim null/curves/*.csv`; the reference, another draw of null, does not;
#  3. the base model's form error is in the data: null against Shard's own tiny beam
#     (scenes/measurements/tiny_bending.toml) is not adequate.
# Prints each set's difference from null in %, the figures of docs/explanation/diagnosis.md "Foreign truth".
#   check_foreign_sets.sh SHARD PLUGIN_DIR SETS WORK
set -euo pipefail
shard=$1 plugins=$2 sets=$3 work=$4
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/../../.." && pwd)
start=$(date +%s)
mkdir -p "$work"
bash "$here/make_foreign_sets.sh" "$shard" "$plugins" "$sets" "$work/synth" > "$work/synth.log" 2>&1 ||
  { cat "$work/synth.log"; exit 1; }
echo "make_foreign_sets.sh: $(( $(date +%s) - start )) s wall"

# feature NAME FIELD FILE: one number of a feature of compare.json (null when not finite).
feature() {
  jq -r --arg name "$1" --arg field "$2" '.features[] | select(.name == $name) | .[$field]' "$3"
}

failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

printf '| set | peak force | peak displacement | stiffness | largest score |\n|---|---|---|---|---|\n'
for set in reference null compliance weibull softening asymmetry toe both; do
  folder=$sets/$set
  "$shard" --plugin-dir "$plugins" compare "$folder" --scene "$here/foreign_beam.toml" --work "$work/model" \
    --out "$work/compare_$set" > "$work/compare_$set.log" 2>&1 || { cat "$work/compare_$set.log"; fail "$set: compare"; continue; }
  jq -e '.format_version == 1' "$work/compare_$set/compare.json" > /dev/null ||
    fail "$set: compare.json is not a version-1 JSON document"
  [[ $set == null ]] && continue
  json=$work/vs_null_$set/compare.json
  "$shard" compare "$folder" --sim "$sets"/null/curves/*.csv --out "$work/vs_null_$set" > /dev/null 2>&1 ||
    { fail "$set: compare with null"; continue; }
  row="| $set |"
  largest=0
  for f in peak_force peak_displacement stiffness; do
    m=$(feature $f measured "$json") s=$(feature $f simulated "$json") score=$(feature $f score "$json")
    row+=$(awk -v m="$m" -v s="$s" -v z="$score" 'BEGIN { printf " %+.1f %% (%.1f u) |", 100 * (m - s) / s, -z }')
    largest=$(awk -v a="$largest" -v z="$score" 'BEGIN { z = z < 0 ? -z : z; print (z > a ? z : a) }')
  done
  echo "$row $largest |"
  if [[ $set == reference ]]; then
    awk -v a="$largest" 'BEGIN { exit !(a < 3) }' || fail "reference differs from null by $largest u"
  else
    awk -v a="$largest" 'BEGIN { exit !(a > 3) }' || fail "$set is within 3 u of null (largest $largest)"
  fi
done

"$shard" compare "$sets/null" --scene "$source_dir/scenes/measurements/tiny_bending.toml" --work "$work/shard_model" \
  --out "$work/null_vs_tiny" > "$work/null_vs_tiny.log" 2>&1 || { cat "$work/null_vs_tiny.log"; fail "null vs tiny_bending"; }
json=$work/null_vs_tiny/compare.json
echo "null against tiny_bending.toml: NRMSE $(jq -r .nrmse "$json"), $(jq -r .verdict "$json")"
jq -e '.adequate == false' "$json" > /dev/null || fail "the foreign null set is adequate against Shard's tiny beam"
echo "total: $(( $(date +%s) - start )) s wall"
exit $(( failures > 0 ))
