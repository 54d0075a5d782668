"""The four-point bending load curve (docs/explanation/four-point-bending.md) from Python: the beam run twice,
at the seed's bond stiffness and 25 % stiffer, and both curves drawn.

    PYTHONPATH=build/release/python python3 python/examples/four_point_bending.py \
        --scene scenes/four_point_bending_ci.toml --out out/py_bending --png four_point_bending.png
"""
import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import shard  # noqa: E402

STIFFNESSES = (12.8e6, 16.0e6)  # Pa: Table I's E_b, and 25 % more


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="scenes/four_point_bending_ci.toml")
    parser.add_argument("--out", default="out/py_bending", help="folder for the runs")
    parser.add_argument("--png", default="four_point_bending.png")
    args = parser.parse_args()

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for stiffness in STIFFNESSES:
        r = shard.run(args.scene, out=Path(args.out) / f"E{stiffness:.3g}",
                      overrides={"bond.youngs_modulus": stiffness})
        label = f"E_b = {stiffness / 1e6:.1f} MPa: peak {r.peak_load:.1f} N at {1e3 * r.displacement_at_peak:.2f} mm"
        ax.plot(1e3 * r.curve.displacement, r.curve.load, label=label)
        ax.plot(1e3 * r.displacement_at_peak, r.peak_load, "k.")
        print(f"{label}; {r.bonds_broken} of {r.bonds_initial} bonds broke; stop: {r.stop_reason}")
    ax.set_xlabel("loading-pin displacement w (mm)")
    ax.set_ylabel("load F (N)")
    ax.set_title(Path(args.scene).name)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)
    print(f"written: {args.png}")


if __name__ == "__main__":
    main()
