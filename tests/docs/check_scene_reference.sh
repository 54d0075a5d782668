#!/usr/bin/env bash
# docs/reference/scene-format.md is what `shard schema` prints: fails, with the difference, when
# the committed page and the command's output differ (a key, a plugin parameter or its doc changed
# without the page being regenerated).
#   check_scene_reference.sh SHARD PAGE
set -euo pipefail
shard=$1 page=$2
# Only the plugins a build ships: a user's SHARD_PLUGIN_PATH would add its own.
printed=$(env -u SHARD_PLUGIN_PATH "$shard" schema)
if ! diff -u "$page" <(printf '%s\n' "$printed"); then
  echo "FAIL: $page differs from \`shard schema\` (above: - the page, + the command)." >&2
  echo "Regenerate it: build/release/bin/shard schema > docs/reference/scene-format.md" >&2
  exit 1
fi
echo "$page is what \`shard schema\` prints ($(wc -l < "$page") lines)"
