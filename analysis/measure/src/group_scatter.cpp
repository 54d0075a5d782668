#include "shard/measure/group_scatter.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "shard/measure/contrast.hpp"
#include "square_matrix.hpp"

namespace shard::measure {
namespace {

using Groups = std::vector<std::vector<std::vector<double>>>;

// The group's own sample covariance (n - 1 in the denominator).
Eigen::MatrixXd own_covariance(const std::vector<std::vector<double>>& rows) {
  double unused = 0;
  return to_matrix(pooled_covariance({rows}, 0.0, unused));
}

struct Pool {
  Eigen::MatrixXd covariance;
  double dof = 0;
};

// The pool of the groups `in` marks, leaving out `skip`; none when fewer than one group of two.
std::optional<Pool> pool_of(const Groups& groups, const std::vector<bool>& in, std::optional<std::size_t> skip,
                            double shrinkage) {
  Groups chosen;
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (in[g] && g != skip) chosen.push_back(groups[g]);
  if (chosen.empty()) return std::nullopt;
  Pool p;
  p.covariance = to_matrix(pooled_covariance(chosen, shrinkage, p.dof));
  return p;
}

struct Ratio {
  double ratio = 1, p = 1;
  std::size_t component = 0;
};

// Component by component, the group's variance over the others' pooled one is F(n_g - 1, nu)
// when they scatter alike; the largest ratio is referred to it with Bonferroni over the
// components (correlated components make that conservative).
Ratio scatter_ratio(const std::vector<std::vector<double>>& rows, const Pool& others) {
  const Eigen::MatrixXd own = own_covariance(rows);
  const auto m = static_cast<double>(own.rows());
  const boost::math::fisher_f_distribution<double> f(static_cast<double>(rows.size()) - 1, others.dof);
  Ratio r;
  for (Eigen::Index i = 0; i < own.rows(); ++i) {
    if (!(others.covariance(i, i) > 0)) continue;
    const double ratio = own(i, i) / others.covariance(i, i);
    const double p = std::min(1.0, m * boost::math::cdf(boost::math::complement(f, ratio)));
    if (i == 0 || ratio > r.ratio) r = {ratio, p, static_cast<std::size_t>(i)};
  }
  return r;
}

// The pooled correlation with, in each component, the larger of the group's own and the pooled
// standard deviation: wider where the group scatters more, and nowhere narrower than the pool (its
// own four specimens cannot show that it scatters less).
Eigen::MatrixXd carried_covariance(const Eigen::MatrixXd& pooled, const Eigen::MatrixXd& own) {
  Eigen::VectorXd scale(pooled.rows());
  for (Eigen::Index i = 0; i < scale.size(); ++i)
    scale(i) = pooled(i, i) > 0 ? std::sqrt(std::max(1.0, own(i, i) / pooled(i, i))) : 1.0;
  return scale.asDiagonal() * pooled * scale.asDiagonal();
}

}  // namespace

GroupScatter group_scatter(const Groups& groups, double shrinkage, double alpha) {
  const std::size_t n = groups.size();
  std::vector<bool> pooled(n);
  std::size_t eligible = 0;
  for (std::size_t g = 0; g < n; ++g) eligible += (pooled[g] = groups[g].size() >= 2);
  std::vector<bool> own(n, false);
  auto in_pool = [&] {
    std::size_t c = 0;
    for (std::size_t g = 0; g < n; ++g) c += pooled[g] && !own[g];
    return c;
  };
  auto pool_mask = [&] {
    std::vector<bool> in(n);
    for (std::size_t g = 0; g < n; ++g) in[g] = pooled[g] && !own[g];
    return in;
  };
  // Set apart one group at a time, the most exceptional first: a second exceptional group in the
  // pool would hide the first.
  while (in_pool() > 2) {
    std::optional<std::size_t> worst;
    double worst_p = 1;
    for (std::size_t g = 0; g < n; ++g) {
      if (!pooled[g] || own[g]) continue;
      const auto others = pool_of(groups, pool_mask(), g, 0.0);
      const Ratio r = scatter_ratio(groups[g], *others);
      if (r.p < worst_p) worst_p = r.p, worst = g;
    }
    if (!worst || worst_p >= alpha / static_cast<double>(eligible)) break;
    own[*worst] = true;
  }
  GroupScatter out;
  const auto final_pool = pool_of(groups, pool_mask(), std::nullopt, shrinkage);
  if (!final_pool) throw std::invalid_argument("contrast: no set has two specimens, so their scatter is unknown");
  out.pooled = from_matrix(final_pool->covariance);
  out.dof = final_pool->dof;
  out.own = own;
  for (std::size_t g = 0; g < n; ++g) {
    Ratio r;
    const auto others = own[g] ? pool_of(groups, pool_mask(), std::nullopt, 0.0) : pool_of(groups, pool_mask(), g, 0.0);
    if (pooled[g] && others) r = scatter_ratio(groups[g], *others);
    out.ratio.push_back(r.ratio);
    out.component.push_back(r.component);
    out.p_value.push_back(r.p);
    out.covariance.push_back(
        own[g] ? from_matrix(carried_covariance(final_pool->covariance, own_covariance(groups[g]))) : out.pooled);
  }
  return out;
}

}  // namespace shard::measure
