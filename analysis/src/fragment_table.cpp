#include "shard/analysis/fragment_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

#include "shard/analysis/components.hpp"

namespace shard::analysis {

namespace {
void require_length(std::size_t expected, std::size_t actual, const char* name) {
  if (actual != expected) {
    throw std::invalid_argument(std::string("particle array '") + name + "' has " +
                                std::to_string(actual) + " entries, expected " +
                                std::to_string(expected));
  }
}

// The body with the largest mass share; only called for the rare fragment with mixed bodies.
std::int32_t dominant_body(const ParticleSample& p, std::span<const Index> labels, Index label) {
  std::map<std::int32_t, double> mass_of_body;
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (labels[v] == label) mass_of_body[p.body[v]] += p.mass[v];
  }
  std::int32_t best = 0;
  double best_mass = -1;
  for (const auto& [body, m] : mass_of_body) {  // ascending body id: ties keep the smallest
    if (m > best_mass) {
      best = body;
      best_mass = m;
    }
  }
  return best;
}
}  // namespace

void check_sample(const ParticleSample& p) {
  const std::size_t n = p.size();
  require_length(n, p.position.size(), "position");
  require_length(n, p.velocity.size(), "velocity");
  require_length(n, p.radius.size(), "radius");
  require_length(n, p.mass.size(), "mass");
  if (!p.body.empty()) require_length(n, p.body.size(), "body");
}

double sphere_volume(double radius) { return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius; }

double equivalent_diameter(double volume) { return std::cbrt(6.0 * volume / std::numbers::pi); }

std::vector<Fragment> fragment_table(const ParticleSample& p, std::span<const Index> labels,
                                     Index count) {
  check_sample(p);
  require_length(p.size(), labels.size(), "labels");
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<Fragment> table(static_cast<std::size_t>(count));
  std::vector<bool> seen(table.size(), false);
  for (std::size_t k = 0; k < table.size(); ++k) {
    table[k].label = static_cast<Index>(k);
    table[k].box_min = Vec3::Constant(inf);
    table[k].box_max = Vec3::Constant(-inf);
    table[k].smallest_id = std::numeric_limits<Index>::max();
  }
  // Accumulate first moments; divide once at the end.
  for (std::size_t v = 0; v < p.size(); ++v) {
    if (labels[v] < 0 || labels[v] >= count) {
      throw std::invalid_argument("fragment label outside [0, count) at particle row " +
                                  std::to_string(v));
    }
    Fragment& f = table[static_cast<std::size_t>(labels[v])];
    const double m = p.mass[v];
    const double r = p.radius[v];
    const std::int32_t body = p.body.empty() ? 0 : p.body[v];
    if (!seen[static_cast<std::size_t>(f.label)]) {
      seen[static_cast<std::size_t>(f.label)] = true;
      f.body = body;
    } else if (body != f.body) {
      f.mixed_bodies = true;
    }
    f.particles += 1;
    f.mass += m;
    f.volume += sphere_volume(r);
    f.centre += m * p.position[v];
    f.velocity += m * p.velocity[v];
    f.box_min = f.box_min.cwiseMin(p.position[v] - Vec3::Constant(r));
    f.box_max = f.box_max.cwiseMax(p.position[v] + Vec3::Constant(r));
    f.smallest_id = std::min(f.smallest_id, p.id[v]);
  }
  for (Fragment& f : table) {
    if (f.particles == 0) throw std::invalid_argument("fragment label with no particle");
    if (f.mass > 0) {
      f.centre /= f.mass;
      f.velocity /= f.mass;
    }
    f.d_eq = equivalent_diameter(f.volume);
    if (f.mixed_bodies) f.body = dominant_body(p, labels, f.label);
  }
  return table;
}

FragmentAnalysis analyse_fragments(const ParticleSample& particles, const BondList& bonds) {
  check_sample(particles);
  FragmentAnalysis result;
  UnionFindLabeller labeller;
  const Index count = labeller.label(particles.size(), bonds, result.labels);
  canonicalise_labels(result.labels, count, particles.mass, particles.id);
  result.fragments = fragment_table(particles, result.labels, count);
  return result;
}

}  // namespace shard::analysis
