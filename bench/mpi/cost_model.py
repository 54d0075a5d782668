#!/usr/bin/env python3
"""The decomposed run's cost model (docs/explanation/scaling.md, "Cost model"), calibrated on measurement
files written by bench/mpi/measure.sh (and bench/mpi/callgrind_split.sh), and its projection.

    python3 bench/mpi/cost_model.py MEASUREMENTS.txt [MORE.txt ...]

time per step on P ranks, for the slowest rank (largest cost, most ghosts, most neighbours):

  compute   = imbalance * (c_p N + c_b B) / P + c_g G          G = ghosts held by the rank
  halo      = 2 k alpha + 19 * 8 G / beta + c_h G              two exchanges a step with k neighbours:
                                                               13 doubles out per ghost, 6 back;
                                                               c_h: packing and unpacking per ghost
  reduction = 2 ceil(log2 P) alpha + P * 8 (2 + 7 W) / beta    one all-gather a step (W walls): an
                                                               MPI_Allgather of the sizes, an MPI_Allgatherv
  partition = (c_m (N/P + G) + 16 cells / beta + ceil(log2 P) alpha) / K   every K steps

Every constant is taken from the measurement lines (CPU time per step of one rank for the compute:
on a shared machine the wall time counts the waiting for a core; best over the repetitions); the
inter-node network figures, the plant scene's shape and the re-partition intervals are assumptions,
printed as such. Nothing of the output is typed in.
"""
import math
import sys
from collections import defaultdict

# Assumed networks (not measured here): latency alpha (s), bandwidth beta (bytes/s).
NETWORKS = {
    "InfiniBand HDR100 (assumed)": (1.5e-6, 12.0e9),
    "10 GbE TCP (assumed)": (30e-6, 1.1e9),
}
SEED_STEPS_TO_FAILURE = (1.44e5, 2.2e5)  # docs/explanation/performance.md: 4-6 mm of pin travel at 20 mm/s
# The 1e7-sphere plant scene (assumed): plates of the belt_to_chute kind (1015 bonds per 283
# spheres), a compact bulk of 1e7 spheres (the ghost and neighbour counts of the partition of a
# 1e7-sphere block, `bench_mpi partition block 10000000`), 10 walls, flowing at up to 3 m/s with a
# skin of 0.1 mm and dt 1e-6 s: a re-partition every 0.5 skin / (v dt) steps.
PLANT_BONDS_PER_SPHERE = 1015 / 283
PLANT_WALLS = 10
PLANT_REPARTITION_EVERY = 0.5 * 1e-4 / (3.0 * 1e-6)
SEED_WALLS = 4
# The seed beam re-partitions when a particle may have moved half the skin (0.2 r_max = 0.1 mm):
# at up to twice the pins' 20 mm/s (assumed: the beam's own motion after the pins land) and dt 1.386e-6 s.
SEED_REPARTITION_EVERY = 0.5 * 1e-4 / (2 * 0.02 * 1.386e-6)
RANKS = (1, 2, 16, 64, 256)


def parse(files):
    lines = []
    for name in files:
        with open(name) as f:
            for raw in f:
                if raw.startswith("#") or not raw.strip():
                    continue
                words = raw.split()
                fields = {"kind": words[0], "label": words[1] if len(words) > 1 else ""}
                for w in words[1:]:
                    if "=" in w:
                        k, v = w.split("=", 1)
                        try:
                            fields[k] = float(v)
                        except ValueError:
                            fields[k] = v
                    else:
                        fields.setdefault("flags", []).append(w)
                lines.append(fields)
    return lines


def pick(lines, kind, label, **match):
    out = []
    for x in lines:
        if x["kind"] != kind or x["label"] != label:
            continue
        if "serial" in match:
            if ("serial" in x.get("flags", [])) != match["serial"]:
                continue
        if all(x.get(k) == v for k, v in match.items() if k != "serial"):
            out.append(x)
    return out


def best(rows, key):
    values = [r[key] for r in rows if key in r]
    return min(values) if values else None


def log2ceil(p):
    return math.ceil(math.log2(p)) if p > 1 else 0


class Model:
    def __init__(self, lines):
        self.notes = []
        one = lambda label: pick(lines, "bench_mpi", label, ranks=1.0, barriers=0.0, serial=False)
        block1, seed1 = one("bonded"), one("scene")
        if not block1:
            sys.exit("no one-rank block line (bench_mpi block 20000 300 on 1 rank)")
        self.block = block1[0]
        t_block = best(block1, "cpu_ms_per_step_max_rank") * 1e-3
        # Per-particle cost from the dense unbonded pack (its contacts included), per-bond cost from
        # the seed beam (330k spheres: out of cache like every large scene); the 18k-sphere block,
        # whose working set fits the caches, checks the pair (the model overestimates it).
        pack = pick(lines, "bench_mpi", "pack", serial=True, threads=1.0)
        if not pack or not seed1:
            sys.exit("need the dense pack's one-thread line and the seed beam's one-rank line")
        self.seed = seed1[0]
        t_seed = best(seed1, "cpu_ms_per_step_max_rank") * 1e-3
        self.c_pack_particle = best(pack, "cpu_ms_per_step") * 1e-3 / pack[0]["particles"]
        self.c_p = self.c_pack_particle
        self.c_b = (t_seed - self.c_p * self.seed["particles"]) / self.seed["bonds"]
        self.t1_seed = t_seed
        predicted = self.c_p * self.block["particles"] + self.c_b * self.block["bonds"]
        self.notes.append(f"c_p from the dense pack's one-thread CPU time per step, c_b from the seed beam's one-rank "
                          f"CPU time ({t_seed*1e3:.1f} ms); check: the block is predicted at {predicted*1e3:.2f} ms "
                          f"against {t_block*1e3:.2f} ms measured ({100*(predicted/t_block-1):+.0f} %: its working set "
                          "fits the caches)")
        self.t1_block = t_block

        # Ghost compute from callgrind: the instructions 2 ranks execute beyond one rank's, per ghost.
        cg1 = [x for x in lines if x["kind"] == "callgrind" and x.get("ranks") == 1.0]
        cg2 = [x for x in lines if x["kind"] == "callgrind" and x.get("ranks") == 2.0]
        self.c_g = 0.0
        if cg1 and cg2:
            steps = cg1[0]["steps"]
            i1 = (cg1[0]["step_Ir"] - cg1[0]["halo_Ir"]) / steps
            i2 = sum(x["step_Ir"] - x["halo_Ir"] for x in cg2) / cg2[0]["steps"]
            ghosts = sum(x["ghosts"] for x in cg2)
            seconds_per_instruction = t_block / ((cg1[0]["step_Ir"] + cg1[0]["finish_Ir"]) / steps)
            raw = (i2 - i1) / ghosts
            self.c_g = max(0.0, raw) * seconds_per_instruction
            self.seconds_per_instruction = seconds_per_instruction
            self.split = [(x["rank"], x["owned"], x["ghosts"], (x["step_Ir"] - x["halo_Ir"]) / x["steps"] / i1,
                           x["halo_Ir"] / x["steps"], x["exchange_Ir"] / x["steps"],
                           (x["halo_Ir"] - x["exchange_Ir"]) / x["steps"] / x["ghosts"]) for x in cg2]
            self.notes.append(f"c_g from callgrind: {raw:.0f} instructions per ghost-step beyond one rank's "
                              f"({(i2 - i1)/1e6:+.2f} M of {i1/1e6:.2f} M per step), at {seconds_per_instruction*1e9:.3f} ns "
                              "per instruction (the one-rank block's CPU time per step)")
        else:
            self.split = []
            self.notes.append("no callgrind lines: c_g = 0")

        pp = [x for x in lines if x["kind"] == "pingpong"]
        if not pp:
            sys.exit("no pingpong lines (mpirun -np 2 bench_mpi pingpong)")
        self.alpha = min(x["best_us"] for x in pp if x["bytes"] <= 8) * 1e-6
        self.beta = max(x["best_MB_per_s"] for x in pp if x["bytes"] >= 262144) * 1e6

        two = pick(lines, "bench_mpi", "bonded", ranks=2.0, barriers=0.0, serial=False)
        ranks2 = [x for x in lines if x["kind"] == "bench_mpi_rank" and x["label"] == "bonded"]
        if not two:
            sys.exit("no two-rank block line")
        ghosts_per_rank = max(x["ghosts"] for x in ranks2 if x.get("neighbours") == 1.0)
        # Packing and unpacking per ghost (both exchanges; the send lists are as long as the
        # neighbour's ghost lists): the smallest over the ranks and runs of any problem.
        per_ghost = [(x["pack_ms"] + x["unpack_ms"]) * 1e-3 / x["ghosts"] for x in lines
                     if x["kind"] == "bench_mpi_rank" and x.get("ghosts", 0) > 0]
        timed_c_h = min(per_ghost)
        if self.split:
            # callgrind: the halo's instructions outside the messages (packing, unpacking, locating
            # by id after a renumbering), per ghost-step, at the block's seconds per instruction.
            self.c_h = min(x[6] for x in self.split) * self.seconds_per_instruction
            self.notes.append(f"c_h from callgrind: {min(x[6] for x in self.split):.0f} instructions per ghost-step in "
                              f"the halo outside the messages (timed under load: {timed_c_h*1e9:.0f} ns, the smallest "
                              f"mean over {len(per_ghost)} rank lines); messages: the pingpong's alpha and beta")
        else:
            self.c_h = timed_c_h
            self.notes.append(f"c_h: the smallest mean packing + unpacking time per ghost-step over the ranks of the "
                              f"two-rank runs ({len(per_ghost)} rank lines); messages: the pingpong's alpha and beta")
        # Re-partition: the CPU time of one re-partition per particle held, on one rank (bench_mpi's
        # repartition_cpu_ms_max: the rank's thread alone, so a shared machine's waiting for a core
        # does not count; on several ranks it would count MPI's polling while the other rank waits
        # for a core), the smallest over the repetitions.
        per_one = [x["repartition_cpu_ms_max"] * 1e-3 / x["particles"] for x in block1 + seed1
                   if x.get("repartitions", 0) > 0 and "repartition_cpu_ms_max" in x]
        if per_one:
            self.c_m = min(per_one)
            self.notes.append(f"c_m: one re-partition's CPU time per particle on one rank ({len(per_one)} runs with a "
                              "re-partition)")
        else:  # measurement files without the re-partition's CPU time: its wall time times the share of a core
            per = []
            for x in block1 + seed1:
                if x.get("repartitions", 0) > 0:
                    share = x["cpu_ms_per_step_max_rank"] / x["ms_per_step"]
                    per.append(share * x["partition_ms_max"] * 1e-3 * x["steps"] / x["repartitions"] / x["particles"])
            self.c_m = min(per) if per else 0.0
            self.notes.append(f"c_m: one rank's re-partition wall time per particle held times its share of a core "
                              f"({len(per)} runs with a re-partition)")
        self.two_block = two
        self.two_seed = pick(lines, "bench_mpi", "scene", ranks=2.0, barriers=0.0, serial=False)
        self.red_measured = best(two, "reduction_min_ms")

        self.partitions = defaultdict(dict)
        self.setups = {}
        for x in lines:
            if x["kind"] == "partition":
                self.partitions[x["label"]][int(x["ranks"])] = x
            elif x["kind"] == "partition_setup":
                self.setups[x["label"]] = x
        self.lines = lines

    def step(self, n, b, ranks, part, cells, walls, every, alpha, beta, c_part=None):
        """Seconds per step on `ranks` ranks (part: the partition line, None for one rank)."""
        if ranks == 1:
            compute, g, k, imb = self.c_p * n + self.c_b * b if c_part is None else c_part, 0.0, 0, 1.0
            return dict(compute=compute, halo=0.0, reduction=0.0, partition=self.c_m * n / every, ghosts=0, k=0)
        g, k, imb = part["ghosts_max"], part["neighbours_max"], part["cost_imbalance"]
        serial = self.c_p * n + self.c_b * b if c_part is None else c_part
        compute = imb * serial / ranks + self.c_g * g
        halo = 2 * k * alpha + 19 * 8 * g / beta + self.c_h * g
        reduction = 2 * log2ceil(ranks) * alpha + ranks * 8 * (2 + 7 * walls) / beta
        partition = (self.c_m * (n / ranks + g) + 16 * cells / beta + log2ceil(ranks) * alpha) / every
        return dict(compute=compute, halo=halo, reduction=reduction, partition=partition, ghosts=g, k=k)


def row(t):
    return sum(t[k] for k in ("compute", "halo", "reduction", "partition"))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    m = Model(parse(sys.argv[1:]))
    print("## Calibrated constants (this machine)\n")
    print(f"- c_p = {m.c_p*1e9:.1f} ns per particle-step, c_b = {m.c_b*1e9:.1f} ns per bond-step (one core)")
    if m.c_pack_particle:
        print(f"- dense unbonded pack: {m.c_pack_particle*1e9:.1f} ns per particle-step (its contacts included)")
    print(f"- c_g = {m.c_g*1e9:.1f} ns of compute per ghost-step; c_h = {m.c_h*1e9:.1f} ns of packing per ghost-step")
    print(f"- intra-node (shared memory, pingpong): alpha = {m.alpha*1e6:.2f} us, beta = {m.beta/1e9:.2f} GB/s")
    print(f"- re-partition: c_m = {m.c_m*1e9:.0f} ns per particle held (owned + ghosts)")
    for n in m.notes:
        print(f"- {n}")
    if m.split:
        print("\nWork split of the 2-rank block (callgrind, per step): "
              + "; ".join(f"rank {r:.0f}: owned {o:.0f}, ghosts {g:.0f}, compute {100*s:.1f} % of one rank's, "
                          f"halo {h/1e6:.2f} M instructions ({e/1e6:.2f} M of them in the messages, MPI's polling "
                          f"included)" for r, o, g, s, h, e, _ in m.split))

    print("\n## Model against measurement, 2 ranks (CPU time per step of the busiest rank, intra-node)\n")
    print("On a shared machine a rank's wall time is mostly waiting for a core; its CPU time is its work "
          "(plus MPI's polling while it waits for the other rank, which the model does not count).\n")
    print("| problem | 1 rank CPU ms | 2 ranks CPU ms (busiest rank) | model 2 ranks: compute + halo ms | pack+unpack ms (mean) | model halo ms |")
    print("|---|---|---|---|---|---|")
    for label, key in (("bonded block", "bonded"), ("seed beam", "scene")):
        one = pick(m.lines, "bench_mpi", key, ranks=1.0, barriers=0.0, serial=False)
        two = pick(m.lines, "bench_mpi", key, ranks=2.0, barriers=0.0, serial=False)
        if not one or not two:
            continue
        x = two[0]
        ranks = [r for r in m.lines if r["kind"] == "bench_mpi_rank" and r["label"] == key and r.get("neighbours") == 1.0]
        ghosts = max(r["ghosts"] for r in ranks)
        packing = min(max(r["pack_ms"] + r["unpack_ms"] for r in ranks[i:i + 2]) for i in range(0, len(ranks), 2))
        part = dict(ghosts_max=ghosts, neighbours_max=1, cost_imbalance=1.0)
        t = m.step(x["particles"], x["bonds"], 2, part, 0, SEED_WALLS, 1e12, m.alpha, m.beta)
        print(f"| {label} | {best(one, 'cpu_ms_per_step_max_rank'):.2f} | {best(two, 'cpu_ms_per_step_max_rank'):.2f} | "
              f"{(t['compute'] + t['halo'])*1e3:.2f} | {packing:.3f} | {t['halo']*1e3:.3f} |")
    print(f"\nReduction, 2 ranks: measured fastest {m.red_measured*1e3:.1f} us, model "
          f"{(2 * m.alpha + 2 * 8 * (2 + 7) / m.beta)*1e6:.1f} us (1 wall; the measured one waits for the other rank's "
          "core on this shared machine).")

    print("\n## OpenMP threads and MPI ranks on the same two cores (ms per step: fastest step / mean wall / CPU)\n")
    print("| problem | OpenMP 1 thread | OpenMP 2 threads | MPI 1 rank | MPI 2 ranks (CPU: busiest rank) | fastest-step ratio OpenMP | MPI |")
    print("|---|---|---|---|---|---|---|")
    for lab, name in (("bonded", "bonded block"), ("scene", "seed beam")):
        rows = [pick(m.lines, "bench_mpi", lab, serial=True, threads=1.0), pick(m.lines, "bench_mpi", lab, serial=True, threads=2.0),
                pick(m.lines, "bench_mpi", lab, ranks=1.0, barriers=0.0, serial=False),
                pick(m.lines, "bench_mpi", lab, ranks=2.0, barriers=0.0, serial=False)]
        if not all(rows):
            continue
        cells = []
        for r in rows:
            cpu = best(r, "cpu_ms_per_step") or best(r, "cpu_ms_per_step_max_rank")
            cells.append(f"{best(r, 'step_min_ms'):.2f} / {best(r, 'ms_per_step'):.2f} / {cpu:.2f}")
        fast = [best(r, "step_min_ms") for r in rows]
        print(f"| {name} | " + " | ".join(cells) + f" | {fast[0]/fast[1]:.2f}x | {fast[2]/fast[3]:.2f}x |")

    scenes = []
    if m.seed is not None and "four_point_bending_seed" in m.partitions:
        s = m.setups["four_point_bending_seed"]
        scenes.append(("seed beam", s["particles"], s["bonds"], None, m.partitions["four_point_bending_seed"], s["cells"],
                       SEED_WALLS, SEED_REPARTITION_EVERY))
    if "block10000000" in m.partitions and m.c_pack_particle:
        s = m.setups["block10000000"]
        n = s["particles"]
        b = PLANT_BONDS_PER_SPHERE * n
        scenes.append(("1e7-sphere plant", n, b, m.c_pack_particle * n + m.c_b * b, m.partitions["block10000000"], s["cells"],
                       PLANT_WALLS, PLANT_REPARTITION_EVERY))
    networks = {"intra-node (measured)": (m.alpha, m.beta)}
    networks.update(NETWORKS)
    for name, n, b, c_part, parts, cells, walls, every in scenes:
        print(f"\n## Projection: {name} ({n:.3g} spheres, {b:.3g} bonds, a re-partition every {every:.0f} steps)\n")
        head = "| network | ranks | ghosts (max) | neighbours (max) | compute ms | halo ms | reductions ms | re-partition ms | ms per step | speed-up | efficiency |"
        if name == "seed beam":
            head += " to failure (1.44e5-2.2e5 steps) |"
        print(head)
        print("|" + "---|" * (head.count("|") - 1))
        base = row(m.step(n, b, 1, None, cells, walls, every, m.alpha, m.beta, c_part))
        for net, (alpha, beta) in networks.items():
            for p in RANKS:
                if p > 1 and p not in parts:
                    continue
                t = m.step(n, b, p, parts.get(p), cells, walls, every, alpha, beta, c_part)
                total = row(t)
                line = (f"| {net} | {p} | {t['ghosts']:.0f} | {t['k']:.0f} | {t['compute']*1e3:.2f} | {t['halo']*1e3:.3f} | "
                        f"{t['reduction']*1e3:.4f} | {t['partition']*1e3:.3f} | {total*1e3:.2f} | {base/total:.1f} | "
                        f"{base/(p*total):.2f} |")
                if name == "seed beam":
                    lo, hi = (s * total / 3600 for s in SEED_STEPS_TO_FAILURE)
                    line += f" {lo:.2f}-{hi:.2f} h |"
                print(line)


if __name__ == "__main__":
    main()
