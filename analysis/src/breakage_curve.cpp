#include "shard/analysis/breakage_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>

#include "shard/analysis/size_distribution.hpp"

namespace shard::analysis {
namespace {

// The pooled distribution of the fragments of `plates` (each plate counted as often as listed).
SizeDistribution pooled(const std::vector<const PlateOutcome*>& plates) {
  std::vector<double> d, mass;
  for (const PlateOutcome* p : plates) {
    d.insert(d.end(), p->fragment_d.begin(), p->fragment_d.end());
    mass.insert(mass.end(), p->fragment_mass.begin(), p->fragment_mass.end());
  }
  return size_distribution(d, mass);
}

// An index uniform in [0, n) from one 64-bit draw (the modulo bias, below n / 2^64, is far below
// any resampling noise). std::uniform_int_distribution is not the same sequence in every standard
// library; this is.
std::size_t uniform_index(std::mt19937_64& rng, std::size_t n) { return static_cast<std::size_t>(rng() % n); }

// The q-quantile of sorted values, linear between order statistics (Hyndman-Fan type 7).
double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const auto k = static_cast<std::size_t>(std::floor(at));
  if (k + 1 >= sorted.size()) return sorted.back();
  return sorted[k] + (at - static_cast<double>(k)) * (sorted[k + 1] - sorted[k]);
}

bool has_fragments(const std::vector<const PlateOutcome*>& plates) {
  for (const PlateOutcome* p : plates)
    if (!p->fragment_d.empty()) return true;
  return false;
}

}  // namespace

Interval bootstrap_x50(const std::vector<const PlateOutcome*>& plates, const CurveOptions& options) {
  if (!(options.level > 0 && options.level < 1)) throw std::invalid_argument("bootstrap_x50: level outside (0, 1)");
  if (!has_fragments(plates)) return {0, 0};
  if (plates.size() == 1 || options.resamples == 0) {
    const double x50 = pooled(plates).x50;
    return {x50, x50};
  }
  std::mt19937_64 rng(options.seed);
  std::vector<double> x50s;
  x50s.reserve(options.resamples);
  std::vector<const PlateOutcome*> draw(plates.size());
  while (x50s.size() < options.resamples) {
    for (auto& p : draw) p = plates[uniform_index(rng, plates.size())];
    if (!has_fragments(draw)) continue;  // only plates without fragments drawn: no distribution
    x50s.push_back(pooled(draw).x50);
  }
  std::sort(x50s.begin(), x50s.end());
  const double tail = 0.5 * (1 - options.level);
  return {quantile(x50s, tail), quantile(x50s, 1 - tail)};
}

BreakageGroup breakage_group(const std::vector<const PlateOutcome*>& plates, const CurveOptions& options) {
  BreakageGroup g;
  g.plates = plates.size();
  std::size_t impacted = 0;
  double speed_sum = 0;
  g.min_speed = std::numeric_limits<double>::infinity();
  g.max_speed = -std::numeric_limits<double>::infinity();
  for (const PlateOutcome* p : plates) {
    g.broken += p->broken ? 1 : 0;
    g.fragments += p->fragment_d.size();
    if (!p->impacted) {
      ++g.not_impacted;
      continue;
    }
    ++impacted;
    speed_sum += p->impact_speed;
    g.min_speed = std::min(g.min_speed, p->impact_speed);
    g.max_speed = std::max(g.max_speed, p->impact_speed);
  }
  if (impacted > 0) {
    g.mean_speed = speed_sum / static_cast<double>(impacted);
  } else {
    g.min_speed = g.max_speed = 0;
  }
  g.broken_share = g.plates > 0 ? static_cast<double>(g.broken) / static_cast<double>(g.plates) : 0;
  g.broken_interval = wilson_interval(g.broken, g.plates, options.z);
  if (has_fragments(plates)) {
    const SizeDistribution fsd = pooled(plates);
    g.x10 = fsd.x10;
    g.x50 = fsd.x50;
    g.x90 = fsd.x90;
    g.x50_interval = bootstrap_x50(plates, options);
  }
  return g;
}

std::vector<double> speed_bin_edges(const std::vector<PlateOutcome>& plates, std::size_t bins) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::size_t impacted = 0;
  for (const PlateOutcome& p : plates) {
    if (!p.impacted) continue;
    ++impacted;
    lo = std::min(lo, p.impact_speed);
    hi = std::max(hi, p.impact_speed);
  }
  if (bins == 0)
    bins = std::clamp<std::size_t>(static_cast<std::size_t>(std::lround(std::sqrt(static_cast<double>(impacted)))), 1, 12);
  if (impacted == 0) return {0.0, 1.0};
  if (!(hi > lo)) {
    // One speed: a bin of +-5 % around it (never empty, never of zero width).
    const double half = std::max(0.05 * std::abs(lo), 1e-6);
    return {lo - half, lo + half};
  }
  std::vector<double> edges(bins + 1);
  for (std::size_t k = 0; k <= bins; ++k)
    edges[k] = lo + (hi - lo) * static_cast<double>(k) / static_cast<double>(bins);
  edges.back() = hi;  // exactly, so the fastest plate falls in the last (closed) bin
  return edges;
}

std::vector<BreakageGroup> breakage_by_speed(const std::vector<PlateOutcome>& plates, const std::vector<double>& edges,
                                             const CurveOptions& options) {
  if (edges.size() < 2) throw std::invalid_argument("speed bins need at least two edges");
  for (std::size_t k = 1; k < edges.size(); ++k)
    if (!(edges[k] > edges[k - 1])) throw std::invalid_argument("speed bin edges must ascend strictly");
  std::vector<std::vector<const PlateOutcome*>> members(edges.size() - 1);
  for (const PlateOutcome& p : plates) {
    if (!p.impacted || p.impact_speed < edges.front() || p.impact_speed > edges.back()) continue;
    // The first edge above the speed closes the bin; the last bin also takes its upper edge.
    auto above = std::upper_bound(edges.begin(), edges.end(), p.impact_speed);
    std::size_t bin = static_cast<std::size_t>(above - edges.begin()) - 1;
    if (bin >= members.size()) bin = members.size() - 1;
    members[bin].push_back(&p);
  }
  std::vector<BreakageGroup> out;
  for (std::size_t k = 0; k < members.size(); ++k) {
    BreakageGroup g = breakage_group(members[k], options);
    g.lower = edges[k];
    g.upper = edges[k + 1];
    out.push_back(g);
  }
  return out;
}

std::vector<BreakageGroup> breakage_by_value(const std::vector<PlateOutcome>& plates, const CurveOptions& options) {
  std::map<double, std::vector<const PlateOutcome*>> members;
  for (const PlateOutcome& p : plates) members[p.value].push_back(&p);
  std::vector<BreakageGroup> out;
  for (const auto& [value, group] : members) {
    BreakageGroup g = breakage_group(group, options);
    g.lower = g.upper = value;
    out.push_back(g);
  }
  return out;
}

}  // namespace shard::analysis
