#!/usr/bin/env python3
"""Writes scenes/data/example_measurement.csv: a SYNTHETIC four-point bending measurement made by
Shard itself, not a laboratory test. It exists to exercise `shard calibrate --measurement`.

Truth: scenes/four_point_bending.toml with another packing (simulation.seed = 11) and bond
parameters E_b = TRUTH_EB, sigma_crit = TRUTH_SIGMA (Table I: 12.8 and 0.24 MPa):

  shard run scenes/four_point_bending.toml --set simulation.seed=11 \
      --set bond.youngs_modulus=17.5e6 --set bond.critical_stress=0.30e6 --out out/truth
  shard bending out/truth/run.h5
  python3 scenes/data/make_example_measurement.py out/truth scenes/data/example_measurement.csv

The displacement column is the beam's own deflection under the pins relative to the supports
(local instrumentation, out/truth/run_local_curve.csv, one row per frame), interpolated
linearly in time onto the force series rows (out/truth/run_bending_curve.csv, every 1 ms);
the rows stop at 60 % of F_max after the peak. Noise: Gaussian, standard deviation 0.5 % of
F_max on the force and 2 um on the deflection, Python random.Random(2026).
"""
import csv
import random
import sys

TRUTH_EB = 17.5e6
TRUTH_SIGMA = 0.30e6
FORCE_NOISE = 0.005   # of F_max
DEFLECTION_NOISE = 2e-6  # m


def read(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return [[float(x) for x in r] for r in rows[1:] if r and not r[0].startswith("#")]


def main(run_dir, out_path):
    series = read(f"{run_dir}/run_bending_curve.csv")   # time_s, displacement_m, force_N
    local = read(f"{run_dir}/run_local_curve.csv")      # time_s, displacement_m (local), force_N
    times = [r[0] for r in local]
    deflection = [r[1] for r in local]

    def local_at(t):
        if t <= times[0]:
            return deflection[0] * t / times[0] if times[0] > 0 else 0.0
        for k in range(1, len(times)):
            if t <= times[k]:
                f = (t - times[k - 1]) / (times[k] - times[k - 1])
                return deflection[k - 1] + f * (deflection[k] - deflection[k - 1])
        return None

    f_max = max(r[2] for r in series)
    peak = max(range(len(series)), key=lambda k: series[k][2])
    rng = random.Random(2026)
    out_rows = []
    for k, (t, _, force) in enumerate(series):
        w = local_at(t)
        if w is None or (k > peak and force < 0.6 * f_max):
            break
        out_rows.append((1e3 * (w + rng.gauss(0.0, DEFLECTION_NOISE)), force + rng.gauss(0.0, FORCE_NOISE * f_max)))
    with open(out_path, "w") as f:
        f.write("# SYNTHETIC four-point bending curve made by Shard, NOT a laboratory measurement.\n")
        f.write("# Made by scenes/data/make_example_measurement.py (its docstring has the commands):\n")
        f.write(f"# scenes/four_point_bending.toml, simulation.seed = 11, bond.youngs_modulus = {TRUTH_EB:.4g} Pa,\n")
        f.write(f"# bond.critical_stress = {TRUTH_SIGMA:.4g} Pa; beam 180 x 30 x 35 mm on supports 170 mm apart, pins 80 mm.\n")
        f.write("# deflection: the beam's own deflection under the pins relative to the supports (local\n")
        f.write("# instrumentation), force: the total force on both pins. Gaussian noise added: 0.5 % of F_max\n")
        f.write("# on the force, 2 um on the deflection (random.Random(2026)).\n")
        f.write("#! span_mm = 170\n#! pin_distance_mm = 80\n#! width_mm = 30\n#! height_mm = 35\n#! displacement = local\n")
        f.write("deflection_mm,force_N\n")
        for w, force in out_rows:
            f.write(f"{w:.5f},{force:.4f}\n")
    print(f"{out_path}: {len(out_rows)} rows, F_max (noise-free) = {f_max:.4g} N")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: make_example_measurement.py <truth run folder> <output.csv>")
    main(sys.argv[1], sys.argv[2])
