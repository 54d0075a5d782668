"""Fragment size distributions of a many-body drop (scenes/plates_drop.toml, docs/reference/bodies.md): the
run's last frame split into fragments, each shard's mass-weighted Q(d) with its impact speed, and
the pooled one.

    PYTHONPATH=build/release/python python3 python/examples/fragment_size_distribution.py \
        --out out/py_plates --png plates_fsd.png
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import shard  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", default="scenes/plates_drop.toml")
    parser.add_argument("--out", default="out/py_plates", help="folder for the run")
    parser.add_argument("--run", help="an existing run.h5 to read instead of running the scene")
    parser.add_argument("--png", default="plates_fsd.png")
    args = parser.parse_args()

    run_file = args.run or shard.run(args.scene, out=args.out, progress=True).run_file
    with shard.RunFile(run_file) as f:
        frame = f.frame(-1)
        bodies = f.body_statistics(-1, intact_fraction=0.9)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for b, speed, fsd in zip(bodies.body, bodies.impact_speed, bodies.distributions):
        ax.step(1e3 * fsd.d, fsd.cumulative, where="post", alpha=0.7,
                label=f"shard {b} at {speed:.2f} m/s: {fsd.fragments} fragments, x50 = {1e3 * fsd.x50:.1f} mm")
    pooled = bodies.pooled
    ax.step(1e3 * pooled.d, pooled.cumulative, where="post", color="k", lw=2,
            label=f"pooled: x10 {1e3 * pooled.x10:.1f}, x50 {1e3 * pooled.x50:.1f}, x90 {1e3 * pooled.x90:.1f} mm")
    ax.set_xlabel("equivalent diameter d (mm)")
    ax.set_ylabel("mass fraction Q(d)")
    ax.set_title(f"t = {1e3 * frame.time:.0f} ms: {bodies.broken_count} of {len(bodies)} shards broken "
                 f"(largest piece < 90 % of the shard)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(args.png, dpi=110)
    print(f"{len(frame)} particles, {len(frame.fragments())} fragments; written: {args.png}")


if __name__ == "__main__":
    main()
