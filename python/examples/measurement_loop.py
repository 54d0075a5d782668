"""A measurement-loop result drawn from Python (docs/tutorials/measurement-loop.md, section 1): synthetic
measurements of the tiny beam with a hidden machine compliance, compared with the base model;
the comparison's curves and residual from compare.json and compare.dat.

    PYTHONPATH=build/release/python python3 python/examples/measurement_loop.py \
        --work out/py_loop --png compare_base.png
"""
import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import shard  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="scenes/measurements/tiny_bending.toml")
    parser.add_argument("--work", default="out/py_loop", help="folder for the measurements, cache and results")
    parser.add_argument("--png", default="compare_base.png")
    args = parser.parse_args()

    work = Path(args.work)
    if not (work / "meas" / "specimens.csv").exists():
        shard.run_cli("synth", scene=args.scene, work=work / "cache", out=work / "meas", seeds=3, scatter=0.02,
                      force_noise=0.01, machine_compliance=3e-4)
    c = shard.compare(work / "meas", out=work / "cmp", scene=args.scene, work=work / "cache", label="base model")
    curves = c.curves
    measured, simulated = curves.split(3)
    w = 1e3 * curves.w
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, height_ratios=(3, 2))
    top.fill_between(w, curves.measured_mean - 2 * curves.u_measured, curves.measured_mean + 2 * curves.u_measured,
                     color="#9ecae1", label="measured mean +-2u")
    for k, curve in enumerate(measured):
        top.plot(w, curve, ":", color="#3182bd", lw=1, label="measured specimens" if k == 0 else None)
    for k, curve in enumerate(simulated):
        top.plot(w, curve, color="#fdae6b", lw=1, label="simulated replicates" if k == 0 else None)
    top.plot(w, curves.simulated_mean, color="#d94801", lw=2, label="simulated mean")
    top.set_ylabel("force F (N)")
    top.set_title(f"NRMSE {100 * c.nrmse:.1f} %: {'adequate' if c.adequate else 'fails beyond noise'}")
    top.legend(fontsize=8, loc="upper left")
    bottom.plot(w, curves.residual, "k.-", ms=3)
    bottom.axhline(2, color="r", ls="--", lw=1)
    bottom.axhline(-2, color="r", ls="--", lw=1)
    bottom.set_ylabel("residual (sigma)")
    bottom.set_xlabel("loading-pin displacement w (mm)")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)
    for name, f in c.features.items():
        if f.judged:
            print(f"{name:18s} measured {f.measured:10.4g} simulated {f.simulated:10.4g} score {f.score:+6.2f}")
    print(f"verdict: {c.verdict}\nwritten: {args.png}")


if __name__ == "__main__":
    main()
