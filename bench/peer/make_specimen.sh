#!/bin/sh
# The peer benchmark specimen (gen_specimen.py: 20 790 spheres on an fcc lattice, 115 553 bonds)
# as Shard's from_file generator reads it, in folder $1 with the scene beside it:
#   sh bench/peer/make_specimen.sh W && build/release/bin/shard run W/peer_beam_shard.toml --out W/s1
set -e
here=$(dirname "$0")
out=${1:?usage: make_specimen.sh FOLDER}
python3 "$here/gen_specimen.py" --out "$out"
python3 - "$out" <<'PY'
import sys
w = sys.argv[1]
def rows(name):
    for line in open(f"{w}/{name}"):
        if line.strip() and not line.startswith("#"):
            yield line.split()
# The box is centred on the beam's axis in x and y, its bottom at z = 0 (the scene's wall positions).
with open(f"{w}/beam.csv", "w") as out:
    out.write("x,y,z,r\n")
    for _, x, y, z, r, _ in rows("specimen.txt"):
        out.write("%.10e,%.10e,%.10e,%.10e\n" % (float(x) - 0.09, float(y) - 0.015, float(z), float(r)))
with open(f"{w}/beam.bonds.csv", "w") as out:
    out.write("i,j\n")
    for i, j in rows("bonds.txt"):
        out.write("%d,%d\n" % (int(i) - 1, int(j) - 1))
PY
cp "$here/peer_beam_shard.toml" "$out/"
