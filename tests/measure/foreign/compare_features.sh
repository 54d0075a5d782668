# Sourced by study_foreign_lab.sh (and its check): reading `shard compare`'s compare.json.
# feature NAME FIELD FILE: one field (measured, simulated, score, ...) of the feature NAME.
feature() { jq -r --arg name "$1" --arg field "$2" '.features[] | select(.name == $name) | .[$field]' "$3"; }
