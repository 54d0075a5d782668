#include "shard/geometry/packing_quality.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "shard/geometry/sphere_grid.hpp"

namespace shard::geometry {
namespace {

Box packing_box(const SpherePacking& packing, double& r_max) {
  Box box{Vec3::Constant(std::numeric_limits<double>::infinity()), Vec3::Constant(-std::numeric_limits<double>::infinity())};
  r_max = 0.0;
  for (std::size_t i = 0; i < packing.centre.size(); ++i) {
    box.lower = box.lower.cwiseMin(packing.centre[i]);
    box.upper = box.upper.cwiseMax(packing.centre[i]);
    r_max = std::max(r_max, packing.radius[i]);
  }
  return box;
}

SphereGrid grid_of(const SpherePacking& packing, double& r_max) {
  const Box box = packing_box(packing, r_max);
  SphereGrid grid(box.lower, box.upper, std::max(2.0 * r_max, 1e-300));
  for (std::size_t i = 0; i < packing.centre.size(); ++i) grid.insert(static_cast<Index>(i), packing.centre[i]);
  return grid;
}

Index find_root(std::vector<Index>& parent, Index i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

BondList bond_by_gap(const SpherePacking& packing, double gap) {
  BondList bonds;
  if (packing.centre.empty()) return bonds;
  double r_max = 0.0;
  const SphereGrid grid = grid_of(packing, r_max);
  for (std::size_t i = 0; i < packing.centre.size(); ++i) {
    const Vec3& ci = packing.centre[i];
    const double ri = packing.radius[i];
    const std::size_t first = bonds.size();
    grid.for_each_near(ci, ri + r_max + gap * 0.5 * (ri + r_max), [&](Index j) {
      if (static_cast<std::size_t>(j) > i) {
        const double rj = packing.radius[j];
        const double reach = (ri + rj) * (1.0 + 0.5 * gap);
        if ((packing.centre[j] - ci).squaredNorm() < reach * reach) bonds.emplace_back(static_cast<Index>(i), j);
      }
      return true;
    });
    std::sort(bonds.begin() + static_cast<std::ptrdiff_t>(first), bonds.end());
  }
  return bonds;
}

std::size_t bond_components(std::size_t particles, const BondList& bonds) {
  std::vector<Index> parent(particles);
  std::iota(parent.begin(), parent.end(), Index{0});
  std::size_t components = particles;
  for (const auto& [i, j] : bonds) {
    const Index a = find_root(parent, i);
    const Index b = find_root(parent, j);
    if (a != b) {
      parent[std::max(a, b)] = std::min(a, b);
      --components;
    }
  }
  return components;
}

double fabric_deviator(const SpherePacking& packing, const BondList& bonds) {
  if (bonds.empty()) return 0.0;
  Mat3 fabric = Mat3::Zero();
  for (const auto& [i, j] : bonds) {
    const Vec3 n = (packing.centre[j] - packing.centre[i]).normalized();
    fabric += n * n.transpose();
  }
  fabric /= static_cast<double>(bonds.size());
  const Mat3 deviator = fabric - Mat3::Identity() * (fabric.trace() / 3.0);
  return deviator.norm();
}

double max_relative_overlap(const SpherePacking& packing) {
  if (packing.centre.empty()) return 0.0;
  double r_max = 0.0;
  const SphereGrid grid = grid_of(packing, r_max);
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < packing.centre.size(); ++i) {
    const double ri = packing.radius[i];
    grid.for_each_near(packing.centre[i], ri + r_max, [&](Index j) {
      if (static_cast<std::size_t>(j) > i) {
        const double rj = packing.radius[j];
        const double overlap = ri + rj - (packing.centre[j] - packing.centre[i]).norm();
        worst = std::max(worst, overlap / std::min(ri, rj));
      }
      return true;
    });
  }
  return worst;
}

double hole_fraction(const SpherePacking& packing, const SignedDistance& distance, const Box& bounds,
                     double d_max, std::size_t samples) {
  double r_max = 0.0;
  const SphereGrid grid = grid_of(packing, r_max);
  const Vec3 extent = bounds.upper - bounds.lower;
  // A regular lattice with about `samples` points in the box (deterministic, no RNG needed).
  const double spacing = std::cbrt(extent.prod() / static_cast<double>(std::max<std::size_t>(samples, 1)));
  std::array<long, 3> count{};
  for (int k = 0; k < 3; ++k) count[k] = std::max(1L, static_cast<long>(std::ceil(extent[k] / spacing)));
  std::size_t inside = 0, holes = 0;
  for (long i = 0; i < count[0]; ++i)
    for (long j = 0; j < count[1]; ++j)
      for (long k = 0; k < count[2]; ++k) {
        const Vec3 p = bounds.lower + Vec3((static_cast<double>(i) + 0.5) * extent.x() / static_cast<double>(count[0]),
                                           (static_cast<double>(j) + 0.5) * extent.y() / static_cast<double>(count[1]),
                                           (static_cast<double>(k) + 0.5) * extent.z() / static_cast<double>(count[2]));
        if (distance(p) > 0.0) continue;
        ++inside;
        const bool near = !grid.for_each_near(p, d_max + r_max, [&](Index id) {
          const double reach = d_max + packing.radius[id];
          return (packing.centre[id] - p).squaredNorm() > reach * reach;
        });
        if (!near) ++holes;
      }
  return inside == 0 ? 0.0 : static_cast<double>(holes) / static_cast<double>(inside);
}

std::vector<std::pair<std::string, double>> packing_quality(const SpherePacking& packing, const BondList& bonds,
                                                            const QualityInputs& inputs) {
  std::vector<std::pair<std::string, double>> q;
  const auto n = static_cast<double>(packing.centre.size());
  q.emplace_back("particles", n);
  q.emplace_back("bonds", static_cast<double>(bonds.size()));
  if (inputs.body_volume > 0.0) {
    double solid = 0.0;
    for (double r : packing.radius) solid += 4.0 / 3.0 * 3.14159265358979323846 * r * r * r;
    q.emplace_back("solid_fraction", solid / inputs.body_volume);
  }
  q.emplace_back("coordination", n > 0 ? 2.0 * static_cast<double>(bonds.size()) / n : 0.0);
  if (inputs.target != nullptr) {
    std::vector<double> diameters(packing.radius.size());
    std::transform(packing.radius.begin(), packing.radius.end(), diameters.begin(), [](double r) { return 2.0 * r; });
    q.emplace_back("psd_ks_distance", inputs.target->ks_distance(std::move(diameters)));
  }
  q.emplace_back("fabric_deviator", fabric_deviator(packing, bonds));
  if (inputs.distance != nullptr && !packing.centre.empty()) {
    const double d_max = 2.0 * *std::max_element(packing.radius.begin(), packing.radius.end());
    q.emplace_back("hole_fraction", hole_fraction(packing, *inputs.distance, inputs.bounds, d_max, inputs.hole_samples));
  }
  q.emplace_back("bond_components", static_cast<double>(bond_components(packing.centre.size(), bonds)));
  q.emplace_back("max_overlap", std::max(0.0, max_relative_overlap(packing)));
  if (inputs.seconds >= 0.0) q.emplace_back("generation_seconds", inputs.seconds);
  return q;
}

std::string format_quality(const std::vector<std::pair<std::string, double>>& quality) {
  std::string line;
  for (const auto& [name, value] : quality) line += fmt::format("{}{}={:.6g}", line.empty() ? "" : " ", name, value);
  return line;
}

}  // namespace shard::geometry
