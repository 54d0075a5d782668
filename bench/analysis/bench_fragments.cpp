// Labels a bonded packing of 3.5e5 particles with 2e6 surviving bonds (a 50 x 70 x 100 lattice,
// 13 neighbour directions, 2e6 of the 4.4e6 candidate bonds kept at random so that the packing
// is partly broken) with both labellers, on one core. Prints one summary line per benchmark:
// best and median wall time over the repetitions. Usage: bench_fragments [repetitions]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "shard/analysis/components.hpp"
#include "shard/analysis/fragment_table.hpp"

using namespace shard;
using namespace shard::analysis;

namespace {

constexpr int kNx = 50, kNy = 70, kNz = 100;  // 350000 particles
constexpr std::size_t kBonds = 2'000'000;

struct Packing {
  std::size_t n = 0;
  std::vector<Index> i, j;
  std::vector<Index> id;
  std::vector<Vec3> position, velocity;
  std::vector<double> radius, mass;
};

Packing make_packing() {
  Packing p;
  p.n = static_cast<std::size_t>(kNx) * kNy * kNz;
  auto at = [](int x, int y, int z) { return static_cast<Index>(x + kNx * (y + kNy * z)); };
  // Half of the 26 neighbour offsets: each lattice bond appears once.
  std::vector<std::array<int, 3>> offsets;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dz > 0 || (dz == 0 && (dy > 0 || (dy == 0 && dx > 0)))) offsets.push_back({dx, dy, dz});
  std::vector<std::pair<Index, Index>> candidates;
  for (int z = 0; z < kNz; ++z)
    for (int y = 0; y < kNy; ++y)
      for (int x = 0; x < kNx; ++x)
        for (const auto& o : offsets) {
          const int X = x + o[0], Y = y + o[1], Z = z + o[2];
          if (X < 0 || X >= kNx || Y < 0 || Y >= kNy || Z >= kNz) continue;
          candidates.emplace_back(at(x, y, z), at(X, Y, Z));
        }
  std::mt19937_64 rng(7);
  for (std::size_t k = 0; k < kBonds; ++k) {  // partial Fisher-Yates: kBonds distinct bonds
    std::uniform_int_distribution<std::size_t> pick(k, candidates.size() - 1);
    std::swap(candidates[k], candidates[pick(rng)]);
  }
  candidates.resize(kBonds);
  std::sort(candidates.begin(), candidates.end());  // the kernel keeps bonds sorted by first particle
  for (const auto& [a, b] : candidates) {
    p.i.push_back(a);
    p.j.push_back(b);
  }
  const double r = 0.5e-3, rho = 2500.0;
  for (std::size_t v = 0; v < p.n; ++v) {
    p.id.push_back(static_cast<Index>(v));
    const auto x = static_cast<double>(v % kNx), y = static_cast<double>((v / kNx) % kNy),
               z = static_cast<double>(v / (kNx * kNy));
    p.position.emplace_back(2 * r * x, 2 * r * y, 2 * r * z);
    p.velocity.emplace_back(0.0, 0.0, 0.0);
    p.radius.push_back(r);
    p.mass.push_back(rho * sphere_volume(r));
  }
  return p;
}

template <class Body>
void bench(const char* name, int repetitions, const Packing& p, Body&& body) {
  std::vector<double> seconds;
  long long result = 0;
  for (int rep = 0; rep < repetitions; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    result = body();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("%-34s particles=%zu bonds=%zu fragments=%lld best=%.4f s median=%.4f s reps=%d\n",
              name, p.n, p.i.size(), result, seconds.front(), seconds[seconds.size() / 2],
              repetitions);
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 7;
  const Packing p = make_packing();
  const BondList bonds{p.i, p.j};
  std::vector<Index> labels;
  CsrComponentLabeller csr;
  UnionFindLabeller uf;
  bench("label_csr_connected_components", repetitions, p,
        [&] { return static_cast<long long>(csr.label(p.n, bonds, labels)); });
  bench("label_union_find", repetitions, p,
        [&] { return static_cast<long long>(uf.label(p.n, bonds, labels)); });
  bench("label_csr+canonical", repetitions, p, [&] {
    const Index count = csr.label(p.n, bonds, labels);
    canonicalise_labels(labels, count, p.mass, p.id);
    return static_cast<long long>(count);
  });
  bench("label_union_find+canonical", repetitions, p, [&] {
    const Index count = uf.label(p.n, bonds, labels);
    canonicalise_labels(labels, count, p.mass, p.id);
    return static_cast<long long>(count);
  });
  bench("analyse_fragments(table)", repetitions, p, [&] {
    const FragmentAnalysis a =
        analyse_fragments({p.id, p.position, p.velocity, p.radius, p.mass, {}}, bonds);
    return static_cast<long long>(a.fragments.size());
  });
  return 0;
}
