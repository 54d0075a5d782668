#!/usr/bin/env python3
"""Overshoot of unstable fracture: how far the force maximum rises above the force at which the
crack starts, from the series of run.h5 files (needs h5py: Debian's python3-h5py).

    foreign_overshoot.py RUN_H5...

Crack initiation, read two ways: the pins' load at the first broken bond (what a model sees), and
the load before the first pop-in, the first fall of the load by 5 % below its running maximum
once a bond has broken (what a lab's curve shows; before any break, the seating's oscillations
at a few N would count). The overshoot is
F_max / F_init - 1. Prints one line per run and the median, smallest and largest overshoot.
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


POP_IN = 0.05  # fall below the running maximum that counts as a pop-in


def pop_in_load(load, start):
    """The running maximum of the load where it first falls POP_IN below it, from sample start on."""
    highest = max(load[: start + 1])
    for value in load[start:]:
        if value < (1 - POP_IN) * highest:
            return highest
        highest = max(highest, value)
    raise ValueError("the load never fell 5 % below its maximum")


def initiation(path):
    """(load at the first broken bond, load before the first pop-in, F_max), N."""
    with h5py.File(path, "r") as f:
        series = f["series"]
        broken = series["bonds_broken"][:]
        load = pin_load(series)
    first = next((k for k, b in enumerate(broken) if b > 0), None)
    if first is None:
        raise ValueError("no bond broke")
    return load[first], pop_in_load(load, first), max(load)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    by_bond, by_pop_in = [], []
    for path in sys.argv[1:]:
        try:
            bond, pop, peak = initiation(path)
        except (OSError, KeyError, ValueError) as e:
            sys.exit(f"{path}: {e}")
        by_bond.append(peak / bond - 1)
        by_pop_in.append(peak / pop - 1)
        print(f"{path}: F_max {peak:.2f} N; first broken bond at {bond:.2f} N (+{100 * by_bond[-1]:.1f} %), "
              f"first pop-in at {pop:.2f} N (+{100 * by_pop_in[-1]:.1f} %)")
    for name, ratios in (("first broken bond", by_bond), ("first pop-in", by_pop_in)):
        print(f"overshoot over the {name}, {len(ratios)} runs: median {100 * statistics.median(ratios):.1f} %, "
              f"range {100 * min(ratios):.1f} .. {100 * max(ratios):.1f} %")


if __name__ == "__main__":
    main()
