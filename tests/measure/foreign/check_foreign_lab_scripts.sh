#!/usr/bin/env bash
# test_foreign_lab_scripts: the lab-scale foreign truth's two scripts on hand-made folders.
#  1. foreign_frame.py adds C F + H F^(2/3), taken from the preload and the zero offset, read to
#     the displacement step: at 58.05 N recorded (58 N after the 0.05 N offset) with C = 3e-5 m/N,
#     H = 1.15e-4 m/N^(2/3), preload 0.5 N: 2 mm + 3.3757 mm - 0.0990 mm = 5.376 mm (1 um steps).
#  2. foreign_confusion.py counts a name as wrong only when it is not in the set's truth: a pair
#     with one true and one false name is one wrong name; "unexplained difference" on an outside
#     effect is none.
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
for s in reference outside pair; do mkdir -p "$draw/sets/$s"; done
printf '[test]\nnotes = "truth: reference"\n' > "$draw/sets/reference/metadata.toml"
printf '[test]\nnotes = "truth: outside"\n' > "$draw/sets/outside/metadata.toml"
printf '[test]\nnotes = "truth: machine_compliance,bond_softening"\n' > "$draw/sets/pair/metadata.toml"
mkdir -p "$draw/diag"
cat > "$draw/diag/diagnose.json" <<'JSON'
{"reference": "reference", "sets": [
 {"name": "outside", "verdict": "unexplained difference"},
 {"name": "pair", "verdict": "machine_compliance + support_friction"}]}
JSON
out=$(python3 "$here/foreign_confusion.py" "$draw")
echo "$out"
grep -q "wrong names: 1$" <<<"$out" || fail "expected one wrong name"
grep -q "set pair named support_friction" <<<"$out" || fail "the wrong name is support_friction on pair"
exit $(( failures > 0 ))
