#!/bin/sh
# Rebuilds docs/images/filter_cake_slab.png: fills the filter-cake shard (seed 1), cuts the
# section z = 17.5 mm and renders it with gnuplot (pngcairo).
#   bench/generator/make_slab_picture.sh <build dir> [output png]
# The build dir must hold bench/generator/slab_picture (cmake --build <dir> --target slab_picture).
set -eu
build=${1:?usage: make_slab_picture.sh <build dir> [output png]}
here=$(cd "$(dirname "$0")" && pwd)
out=${2:-$here/../../docs/images/filter_cake_slab.png}
data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
"$build/bench/generator/slab_picture" "$data" 17.5 0.7
gnuplot -e "dir='$data'; out='$out'" "$here/slab_picture.gp"
echo "wrote $out"
