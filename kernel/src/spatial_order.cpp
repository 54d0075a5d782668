#include "spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "huge_pages.hpp"
#include "parallel.hpp"
#include "shard/particle_arrays.hpp"

namespace shard {
namespace {

// Spreads the low 21 bits of v so that two zero bits follow each one.
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// The gathers write into scratch arrays on huge pages (huge_pages.hpp), which then become the live
// ones. The first time, the former live arrays (ordinary pages, as the scene was built) are freed
// rather than kept as scratch, so the next reordering takes advised storage for them too and the
// live arrays stay on huge pages from then on.
template <class T>
void swap_in(std::vector<T>& live, std::vector<T>& scratch, bool release_old) {
  live.swap(scratch);
  if (release_old) std::vector<T>().swap(scratch);
}

template <class T>
void gather(std::vector<T>& live, std::vector<T>& scratch, const Index* order, std::size_t n, bool release_old) {
  resize_on_huge_pages(scratch, n);
#pragma omp parallel for schedule(static) num_threads(team_for(n))
  for (std::size_t k = 0; k < n; ++k) scratch[k] = live[static_cast<std::size_t>(order[k])];
  swap_in(live, scratch, release_old);
}

template <class T>
void gather(std::vector<T>& live, std::vector<T>& scratch, const std::vector<std::size_t>& order, bool release_old) {
  const std::size_t n = order.size();
  resize_on_huge_pages(scratch, n);
#pragma omp parallel for schedule(static) num_threads(team_for(n))
  for (std::size_t k = 0; k < n; ++k) scratch[k] = live[order[k]];
  swap_in(live, scratch, release_old);
}

}  // namespace

bool SpatialOrder::compute(const Particles& particles, double cell) {
  const std::size_t n = particles.size();
  if (n == 0) return false;
  Vec3 lo = particles.position[0];
  for (const Vec3& x : particles.position) lo = lo.cwiseMin(x);
  constexpr double kMaxCoordinate = double((1 << 21) - 1);
  keys_.resize(n);
#pragma omp parallel for schedule(static) num_threads(team_for(n))
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t key = 0;
    for (int a = 0; a < 3; ++a) {
      const double q = std::clamp(std::floor((particles.position[k][a] - lo[a]) / cell), 0.0, kMaxCoordinate);
      key |= spread_bits(static_cast<std::uint64_t>(q)) << a;
    }
    keys_[k] = {key, static_cast<Index>(k)};
  }
  // Ties (same cell) keep index order: the order is a function of the state alone.
  std::sort(keys_.begin(), keys_.end());
  order_.resize(n);
  new_index_.resize(n);
  bool changed = false;
  for (std::size_t k = 0; k < n; ++k) {
    order_[k] = keys_[k].second;
    new_index_[static_cast<std::size_t>(order_[k])] = static_cast<Index>(k);
    changed = changed || order_[k] != static_cast<Index>(k);
  }
  return changed;
}

void SpatialOrder::apply(Particles& p, Bonds& bonds) {
  const std::size_t n = p.size();
  const Index* order = order_.data();
  const bool release = !live_on_huge_pages_;
  live_on_huge_pages_ = true;
  for_each_particle_array([&](auto& live, auto& spare) { gather(live, spare, order, n, release); }, p, scratch_);

  // Bonds: rename the ends (each keeps its orientation: a bond model may store state relative to
  // its first end), then a stable counting sort by the smaller end.
  const std::size_t m = bonds.size();
  if (m == 0) return;
  for (std::size_t k = 0; k < m; ++k) {
    bonds.i[k] = new_index_[static_cast<std::size_t>(bonds.i[k])];
    bonds.j[k] = new_index_[static_cast<std::size_t>(bonds.j[k])];
  }
  const auto key = [&](std::size_t k) { return static_cast<std::size_t>(std::min(bonds.i[k], bonds.j[k])); };
  bond_start_.assign(n + 1, 0);
  for (std::size_t k = 0; k < m; ++k) ++bond_start_[key(k) + 1];
  std::partial_sum(bond_start_.begin(), bond_start_.end(), bond_start_.begin());
  bond_order_.resize(m);
  for (std::size_t k = 0; k < m; ++k) bond_order_[static_cast<std::size_t>(bond_start_[key(k)]++)] = k;
  gather(bonds.i, bond_scratch_.i, bond_order_, release);
  gather(bonds.j, bond_scratch_.j, bond_order_, release);
  if (bonds.keeps_loads) {
    gather(bonds.force, bond_scratch_.force, bond_order_, release);
    gather(bonds.torque_i, bond_scratch_.torque_i, bond_order_, release);
    gather(bonds.torque_j, bond_scratch_.torque_j, bond_order_, release);
    gather(bonds.energy, bond_scratch_.energy, bond_order_, release);
  }
  gather(bonds.broken, bond_scratch_.broken, bond_order_, release);
  gather(bonds.stress, bond_scratch_.stress, bond_order_, release);
  const std::size_t stride = bonds.stride;
  resize_on_huge_pages(bond_scratch_.state, m * stride);
#pragma omp parallel for schedule(static) num_threads(team_for(m))
  for (std::size_t k = 0; k < m; ++k)
    std::copy_n(bonds.state.begin() + static_cast<std::ptrdiff_t>(bond_order_[k] * stride), stride,
                bond_scratch_.state.begin() + static_cast<std::ptrdiff_t>(k * stride));
  swap_in(bonds.state, bond_scratch_.state, release);
}

}  // namespace shard
