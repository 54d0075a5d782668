#!/usr/bin/env python3
"""A load frame of another form than Shard's machine_compliance (C F, linear): a column spring in
series with Hertzian seats where the rollers bear on their blocks,
    d_frame(F) = C F + H F^(2/3),
added to the crosshead displacement of every curve of a measurement set that `shard synth` made
(t = 0, d = 0 at the seating preload; forces carry the set's zero offset). The frame's displacement
is taken from the preload, and the sum is read to the set's displacement step again.

    foreign_frame.py SET C H STEP
      SET   measurement folder (curves/*.csv and metadata.toml), rewritten in place
      C     linear frame compliance, m/N
      H     Hertzian seat coefficient, m/N^(2/3)
      STEP  displacement resolution of the set, m
"""
import glob
import os
import re
import sys


def test_value(metadata, key):
    """A number of metadata.toml's [test] table, 0 when absent."""
    match = re.search(r"^\s*" + key + r"\s*=\s*([-+0-9.eE]+)", metadata, re.MULTILINE)
    return float(match.group(1)) if match else 0.0


def frame(force, linear, hertz):
    load = max(force, 0.0)
    return linear * load + hertz * load ** (2.0 / 3.0)


def rewrite(path, linear, hertz, step, preload, zero):
    with open(path) as f:
        lines = f.read().splitlines()
    header, rows = lines[0], lines[1:]
    if not header.startswith("time,displacement,force"):
        sys.exit(f"{path}:1: expected the header time,displacement,force,...; not a curve of shard synth")
    seated = frame(preload, linear, hertz)
    out = [header]
    for number, row in enumerate(rows, start=2):
        cells = row.split(",")
        try:
            displacement, force = float(cells[1]), float(cells[2])
        except (IndexError, ValueError):
            sys.exit(f"{path}:{number}: displacement and force must be numbers, got '{row}'")
        moved = displacement + frame(force - zero, linear, hertz) - seated
        cells[1] = f"{round(moved / step) * step:.9g}"
        out.append(",".join(cells))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    folder = sys.argv[1]
    linear, hertz, step = (float(v) for v in sys.argv[2:5])
    if linear < 0 or hertz < 0 or step <= 0:
        sys.exit("foreign_frame.py: C and H must be >= 0 and STEP > 0")
    with open(os.path.join(folder, "metadata.toml")) as f:
        metadata = f.read()
    preload, zero = test_value(metadata, "seating_preload"), test_value(metadata, "zero_offset")
    curves = sorted(glob.glob(os.path.join(folder, "curves", "*.csv")))
    if not curves:
        sys.exit(f"{folder}/curves: no curve files; make the set with shard synth first")
    for path in curves:
        rewrite(path, linear, hertz, step, preload, zero)


if __name__ == "__main__":
    main()
