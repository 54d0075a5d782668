#!/usr/bin/env python3
"""Overshoot of unstable fracture: how far the force maximum rises above the force at which the
crack starts, from the series of run.h5 files (needs h5py: Debian's python3-h5py).

    foreign_overshoot.py RUN_H5...

Crack initiation: the first series sample with a broken bond; the force there is the pins' load
F_init, the maximum over the run F_max, the overshoot F_max / F_init - 1. Prints one line per run
and the median, smallest and largest overshoot.
"""
import statistics
import sys

try:
    import h5py
except ImportError:
    sys.exit("foreign_overshoot.py needs h5py: apt-get install python3-h5py, and run it with /usr/bin/python3")


def pin_load(series):
    """The pins' load (N) at every sample: the z forces of the walls named pin_*, pushing down."""
    walls = series["walls"]
    pins = [name for name in walls if name.startswith("pin")]
    if not pins:
        raise ValueError("no wall named pin_* in series/walls")
    total = sum(walls[name]["force"][:, 2] for name in pins)
    return [abs(v) for v in total]


def overshoot(path):
    with h5py.File(path, "r") as f:
        series = f["series"]
        broken = series["bonds_broken"][:]
        load = pin_load(series)
    first = next((k for k, b in enumerate(broken) if b > 0), None)
    if first is None:
        raise ValueError("no bond broke")
    return load[first], max(load)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    ratios = []
    for path in sys.argv[1:]:
        try:
            initiation, peak = overshoot(path)
        except (OSError, KeyError, ValueError) as e:
            sys.exit(f"{path}: {e}")
        ratios.append(peak / initiation - 1)
        print(f"{path}: F_init {initiation:.2f} N, F_max {peak:.2f} N, overshoot {100 * ratios[-1]:.1f} %")
    print(f"overshoot over {len(ratios)} runs: median {100 * statistics.median(ratios):.1f} %, "
          f"range {100 * min(ratios):.1f} .. {100 * max(ratios):.1f} %")


if __name__ == "__main__":
    main()
