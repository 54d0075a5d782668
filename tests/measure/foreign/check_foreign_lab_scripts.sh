#!/usr/bin/env bash
# test_foreign_lab_scripts: the lab-scale foreign truth's two scripts on hand-made folders.
#  1. foreign_frame.py adds C F + H F^(2/3), taken from the preload and the zero offset, read to
#     the displacement step: at 58.05 N recorded (58 N after the 0.05 N offset) with C = 3e-5 m/N,
#     H = 1.15e-4 m/N^(2/3), preload 0.5 N: 2 mm + 3.3757 mm - 0.0990 mm = 5.376 mm (1 um steps).
#  2. foreign_confusion.py counts a name as wrong only when it is not in the set's truth: a pair
#     with one true and one false name is one wrong name; "unexplained difference" on an outside
#     effect is none. Its targets: the outside set never named (met), the pair given a wrong name
#     (not met), a single effect named in 1 of the 1 draws with p < 1e-3 (met), a null set named
#     (not met). The two-rate sets' own diagnosis (diag_rates) is counted too: a rate set named as
#     another effect is a third wrong name, and a set in both reports is counted once. With
#     --model flat_zones the draw's diag_flat_zones is read instead; study_foreign_lab.sh refuses
#     a STUDY_MODEL it does not know (exit 2, naming the two it has).
#  3. compare_features.sh reads a feature's field from compare.json as the JSON writer lays it
#     out (one key per line).
#   check_foreign_lab_scripts.sh WORK
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$1
rm -rf "$work" && mkdir -p "$work/set/curves"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

printf 'name = "x"\n\n[test]\nseating_preload = 0.5   # N\nzero_offset = 0.05   # N\n' > "$work/set/metadata.toml"
printf 'time,displacement,force,u_displacement,u_force\n0,0,0.55,2.9e-07,0.05\n0.1,0.002,58.05,2.9e-07,0.05\n' \
  > "$work/set/curves/a.csv"
python3 "$here/foreign_frame.py" "$work/set" 3e-5 1.15e-4 1e-6
first=$(sed -n 2p "$work/set/curves/a.csv" | cut -d, -f2) last=$(sed -n 3p "$work/set/curves/a.csv" | cut -d, -f2)
[[ $first == 0 ]] || fail "the preload point moved to $first m"
[[ $last == 0.005376 ]] || fail "at 58 N the frame gave $last m, expected 0.005376 m"

draw=$work/draw
for s in reference outside pair softening null rates; do mkdir -p "$draw/sets/$s"; done
printf '[test]\nnotes = "truth: bond_viscosity"\n' > "$draw/sets/rates/metadata.toml"
mkdir -p "$draw/diag_rates"
cat > "$draw/diag_rates/diagnose.json" <<'JSON'
{"reference": "reference", "sets": [
 {"name": "null", "verdict": "no difference", "p_value": 0.4},
 {"name": "rates", "verdict": "weibull_strength", "p_value": 1e-20}]}
JSON
printf '[test]\nnotes = "truth: reference"\n' > "$draw/sets/reference/metadata.toml"
printf '[test]\nnotes = "truth: outside"\n' > "$draw/sets/outside/metadata.toml"
printf '[test]\nnotes = "truth: machine_compliance,bond_softening"\n' > "$draw/sets/pair/metadata.toml"
printf '[test]\nnotes = "truth: bond_softening"\n' > "$draw/sets/softening/metadata.toml"
printf '[test]\nnotes = "truth: none"\n' > "$draw/sets/null/metadata.toml"
mkdir -p "$draw/diag"
cat > "$draw/diag/diagnose.json" <<'JSON'
{"reference": "reference", "sets": [
 {"name": "outside", "verdict": "unexplained difference", "p_value": 1e-9},
 {"name": "pair", "verdict": "machine_compliance + support_friction", "p_value": 1e-12},
 {"name": "softening", "verdict": "bond_softening", "p_value": 2e-4},
 {"name": "null", "verdict": "weibull_strength", "p_value": 0.02}]}
JSON
out=$(python3 "$here/foreign_confusion.py" "$draw")
echo "$out"
grep -q "wrong names: 3$" <<<"$out" || fail "expected three wrong names"
grep -q "set rates named weibull_strength" <<<"$out" || fail "a wrong name is weibull_strength on rates"
grep -q "| null | none | weibull_strength 1 |" <<<"$out" || fail "the null set is counted once, from diag"
grep -q "set pair named support_friction" <<<"$out" || fail "a wrong name is support_friction on pair"
grep -q "set null named weibull_strength" <<<"$out" || fail "a wrong name is weibull_strength on null"
grep -q "| outside | never named: 1 of 1 | yes |" <<<"$out" || fail "the outside set's target is met"
grep -q "| pair | both named or unexplained: 0 of 1 | no |" <<<"$out" || fail "the pair's target is not met"
grep -q "| softening | named in 1 of 1 draws with p < 1e-3 | yes |" <<<"$out" || fail "softening's target is met"
grep -q "| null | no difference in every draw: 0 of 1 | no |" <<<"$out" || fail "the null set's target is not met"
# Another model's diagnoses (study_foreign_lab.sh's STUDY_MODEL) are read from their own folders.
mkdir -p "$draw/diag_flat_zones"
cat > "$draw/diag_flat_zones/diagnose.json" <<'JSON'
{"reference": "reference", "sets": [
 {"name": "null", "verdict": "no difference", "p_value": 0.3}]}
JSON
out=$(python3 "$here/foreign_confusion.py" --model flat_zones "$draw")
grep -q "wrong names: 0$" <<<"$out" || fail "flat_zones: expected no wrong name (its own diagnosis, no diag_rates_flat_zones)"
grep -q "| null | none | no difference 1 |" <<<"$out" || fail "flat_zones: the null set from diag_flat_zones"
# A model the study does not know is refused before anything runs, naming the fix.
rc=0
err=$(STUDY_MODEL=flat bash "$here/study_foreign_lab.sh" /nonexistent/shard "$work/none" 0 2>&1 >/dev/null) || rc=$?
[[ $rc == 2 ]] || fail "STUDY_MODEL=flat: exit $rc, expected 2"
grep -q "STUDY_MODEL=random or flat_zones" <<<"$err" || fail "STUDY_MODEL=flat: the message names no fix: $err"
source "$here/compare_features.sh"
cat > "$work/compare.json" <<'JSON'
{
  "format_version": 1,
  "features": [
    {
      "name": "stiffness",
      "measured": 12980.04,
      "score": 0.70
    },
    {
      "name": "peak_force",
      "measured": 63.956,
      "simulated": 64.815,
      "score": 0.96
    }
  ]
}
JSON
[[ $(feature peak_force simulated "$work/compare.json") == 64.815 ]] || fail "peak_force simulated: expected 64.815"
[[ $(feature stiffness score "$work/compare.json") == 0.70 || $(feature stiffness score "$work/compare.json") == 0.7 ]] ||
  fail "stiffness score: expected 0.7"
exit $(( failures > 0 ))
