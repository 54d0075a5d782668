#!/usr/bin/env bash
# Settle/impact throughput of scenes/belt_to_chute.toml (docs/explanation/performance.md, "The figures"):
# particle-steps per second on 1 and 2 threads, and their growth with the number of plates.
#   bench/process/bench_belt_to_chute.sh [build/release/bin/shard] [window_s=0.8] [plates="5 10 20 40"]
# Each run simulates the first `window_s` seconds: the plates ride the belt, the front ones leave it,
# strike the chute and break. The plates lie at the default scene's density along the belt (one per
# 78 mm of belt, two lanes: the stream's region starts 0.06 m behind the head end and reaches
# 0.078 m x plates back, 3.18 m for 40 plates on the 3.5 m belt), so the same number strike per second
# whatever the count. One line per run: plates, threads, particles, steps, wall and CPU seconds,
# particle-steps per wall second and per CPU second (the CPU figure is the one to compare on a
# shared machine), bonds broken, and the load average (1 min) before and after the run. Then the
# growth: per thread count, the CPU time per particle-step relative to the smallest plate count
# (1.00 = linear growth of the cost with the particles), and the 2-thread wall speed-up.
set -euo pipefail
shard=${1:-build/release/bin/shard}
window=${2:-0.8}
plates=${3:-"5 10 20 40"}
root=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
load() { cut -d' ' -f1 /proc/loadavg; }
echo "plates threads particles steps wall_s cpu_s particle_steps_per_s particle_steps_per_cpu_s bonds_broken load_before load_after"
for n in $plates; do
  xmin=$(awk -v n="$n" 'BEGIN { printf "%.3f", -0.06 - 0.078 * n }')
  for threads in 1 2; do
    log="$out/run_${n}_${threads}.log"
    before=$(load)
    OMP_NUM_THREADS=$threads OMP_WAIT_POLICY=passive /usr/bin/time -f "%e %U %S" -o "$out/time" \
      "$shard" run "$root/scenes/belt_to_chute.toml" --out "$out/run" \
      --set "body.plate.stream.copies=$n" --set "body.plate.stream.region_min=[$xmin, -0.07, 0.619]" \
      --set "simulation.duration=$window" --set "output.frame_interval=$window" >"$log" 2>&1
    after=$(load)
    read -r wall user sys <"$out/time"
    particles=$(sed -n 's/^scene .*: \([0-9]*\) particles.*/\1/p' "$log")
    steps=$(sed -n 's/^done: .*; \([0-9]*\) steps, .*/\1/p' "$log")
    broken=$(sed -n 's/^done: .*, \([0-9]*\) bonds broken.*/\1/p' "$log")
    awk -v n="$n" -v t="$threads" -v p="$particles" -v s="$steps" -v w="$wall" -v u="$user" -v y="$sys" -v b="$broken" \
      -v l0="$before" -v l1="$after" \
      'BEGIN { c = u + y; printf "%d %d %d %d %.1f %.1f %.3g %.3g %d %s %s\n", n, t, p, s, w, c, p * s / w, p * s / c, b, l0, l1 }' |
      tee -a "$out/table"
  done
done
echo
echo "growth: plates threads cpu_ns_per_particle_step relative_to_first speedup_2_threads_wall"
awk '{ key = $1 " " $2; ns[key] = 1e9 * $6 / ($3 * $4); wall[key] = $5; if (!($2 in first)) first[$2] = ns[key];
       order[++k] = key }
     END { for (i = 1; i <= k; ++i) { split(order[i], f, " ");
             up = (f[2] == 2 && (f[1] " 1") in wall) ? sprintf("%.2f", wall[f[1] " 1"] / wall[order[i]]) : "-";
             printf "%s %s %.0f %.2f %s\n", f[1], f[2], ns[order[i]], ns[order[i]] / first[f[2]], up } }' "$out/table"
