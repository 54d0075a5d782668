#include "shard/measure/diagnosis.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "shard/measure/statistics.hpp"

namespace shard::measure {
namespace {

Eigen::VectorXd to_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

Eigen::MatrixXd jacobian_matrix(const std::vector<std::vector<double>>& jacobian, Eigen::Index m) {
  const auto p = static_cast<Eigen::Index>(jacobian.size());
  if (p >= m) throw std::invalid_argument("diagnose: more base parameters than residual components");
  Eigen::MatrixXd J(m, p);
  for (Eigen::Index c = 0; c < p; ++c) {
    if (static_cast<Eigen::Index>(jacobian[static_cast<std::size_t>(c)].size()) != m)
      throw std::invalid_argument("diagnose: a Jacobian column has the wrong length");
    J.col(c) = to_vector(jacobian[static_cast<std::size_t>(c)]);
  }
  return J;
}

// The components whose |residual| drops most when the fitted effect is added (at most four, each
// more than a tenth of the score).
std::vector<std::string> explained_components(const std::vector<std::string>& names, const Eigen::VectorXd& y,
                                              const Eigen::VectorXd& after, double score) {
  std::vector<std::size_t> order(static_cast<std::size_t>(y.size()));
  std::iota(order.begin(), order.end(), 0);
  auto gain = [&](std::size_t i) {
    const auto k = static_cast<Eigen::Index>(i);
    return y[k] * y[k] - after[k] * after[k];
  };
  std::sort(order.begin(), order.end(), [&](auto x, auto z) { return gain(x) > gain(z); });
  std::vector<std::string> out;
  for (auto i : order)
    if (gain(i) > 0.1 * score && out.size() < 4) out.push_back(names[i]);
  return out;
}

// How often the packing seeds alone would agree as well on the move towards zero: each seed's
// move at size a along -y, g_k = -a s_k . y (y is orthogonal to the base columns, so
// s_k . y = t_k . y), tested by mean_above_zero_p; 0 (not tested) with fewer than two seeds.
double seed_agreement_p(const EffectSignature& e, double a, const Eigen::VectorXd& y) {
  if (e.seed_signatures.size() < 2) return 0;
  std::vector<double> towards_zero;
  for (const auto& seed : e.seed_signatures) {
    if (static_cast<Eigen::Index>(seed.size()) != y.size())
      throw std::invalid_argument(fmt::format("diagnose: a seed signature of '{}' has the wrong length", e.name));
    towards_zero.push_back(-a * y.dot(to_vector(seed)));
  }
  return mean_above_zero_p(towards_zero);
}

// An effect's score on the unabsorbed residual y, with t its signature projected off the base
// parameters' columns.
EffectScore score_effect(const EffectSignature& e, const Eigen::VectorXd& t, const Eigen::VectorXd& y,
                         const std::vector<std::string>& names, const Diagnosis& d, const DiagnoseOptions& options) {
  EffectScore s;
  s.name = e.name;
  const double tt = t.squaredNorm();
  const double ss = to_vector(e.signature).squaredNorm();
  s.absorbed = ss > 0 ? 1 - tt / ss : 1;
  if (tt > 1e-12 * std::max(1.0, ss)) {
    // Score of the best admissible size: the drop |y|^2 - |y + a t|^2 = -2 a t.y - a^2 |t|^2 at
    // a clamped into the effect's physical range. Unclamped it is the LM statistic (t.y)^2 / |t|^2;
    // an effect the data want reversed (a negative compliance) scores 0 and explains nothing.
    const double ty = t.dot(y);
    const double free_a = -ty / tt;
    const double a = std::clamp(free_a, e.scale_min, e.scale_max);
    s.at_bound = a != free_a;
    s.score = std::max(0.0, -2 * a * ty - a * a * tt);
    s.size = a * e.trial_size;
    s.explains = explained_components(names, y, y + a * t, s.score);
    s.seed_p = seed_agreement_p(e, a, y);
    s.resolved = s.seed_p < options.seed_p;
  }
  s.identifiable = e.identifiable;
  s.p_value = chi_square_survival(s.score, 1);
  s.explained = d.chi_square_unabsorbed > 0 ? s.score / d.chi_square_unabsorbed : 0;
  s.chi_square_after = d.chi_square_unabsorbed - s.score;
  s.delta_aic = -s.score + 2;
  s.delta_bic = -s.score + std::log(static_cast<double>(y.size()));
  return s;
}

// Two tests of "the base model is right": the omnibus chi^2(m - p) over every direction, and the
// score test of each candidate, Bonferroni-corrected over the n candidates (the best of n
// reaches p by chance n times as often). The omnibus test dilutes one strong direction over
// m - p degrees of freedom, so a focused candidate can be significant while it passes; the
// data are adequate only when neither rejects (false alarms <= adequate_p + significant_p).
// Only an effect the packing seeds resolve (EffectScore::resolved) is a focused candidate.
std::string verdict_of(const Diagnosis& d, const DiagnoseOptions& options) {
  const auto best = std::find_if(d.ranking.begin(), d.ranking.end(), [](const EffectScore& s) { return s.resolved; });
  const bool focused =
      best != d.ranking.end() && best->p_value < options.significant_p / static_cast<double>(d.ranking.size());
  if (d.p_value > options.adequate_p && !focused) return "adequate";
  if (focused && best->explained >= options.min_explained && best->identifiable) return best->name;
  return "unexplained structured residual";
}

}  // namespace

Diagnosis diagnose(const std::vector<std::string>& names, const std::vector<double>& residual,
                   const std::vector<std::vector<double>>& jacobian, const std::vector<EffectSignature>& effects,
                   const DiagnoseOptions& options) {
  const auto m = static_cast<Eigen::Index>(residual.size());
  if (names.size() != residual.size()) throw std::invalid_argument("diagnose: names and residual differ in length");
  const Eigen::MatrixXd J = jacobian_matrix(jacobian, m);
  // Orthonormal basis of the base parameters' column space (QR is stable when they are nearly
  // collinear, where (J^T J)^-1 would not be).
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(J);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(m, J.cols());
  auto project = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return v - Q * (Q.transpose() * v); };

  Diagnosis d;
  const Eigen::VectorXd r0 = to_vector(residual);
  const Eigen::VectorXd y = project(r0);
  d.chi_square = r0.squaredNorm();
  d.chi_square_unabsorbed = y.squaredNorm();
  d.p_value = chi_square_survival(d.chi_square_unabsorbed, static_cast<double>(m - J.cols()));
  std::vector<Eigen::VectorXd> projected;
  for (const auto& e : effects) {
    if (static_cast<Eigen::Index>(e.signature.size()) != m)
      throw std::invalid_argument(fmt::format("diagnose: signature of '{}' has the wrong length", e.name));
    projected.push_back(project(to_vector(e.signature)));
    d.ranking.push_back(score_effect(e, projected.back(), y, names, d, options));
  }
  for (std::size_t a = 0; a < projected.size(); ++a)
    for (std::size_t b = a + 1; b < projected.size(); ++b) {
      const double na = projected[a].norm(), nb = projected[b].norm();
      if (na > 0 && nb > 0 && std::abs(projected[a].dot(projected[b])) / (na * nb) > options.collinear_cosine)
        d.indistinguishable.emplace_back(effects[a].name, effects[b].name);
    }
  std::stable_sort(d.ranking.begin(), d.ranking.end(), [](const auto& x, const auto& z) { return x.score > z.score; });
  d.verdict = verdict_of(d, options);
  return d;
}

}  // namespace shard::measure

namespace shard::measure {

LinearRefit linear_refit(const std::vector<double>& residual, const std::vector<std::vector<double>>& jacobian,
                         const std::vector<EffectSignature>& effects) {
  const auto m = static_cast<Eigen::Index>(residual.size());
  const auto p = static_cast<Eigen::Index>(jacobian.size());
  const auto q = static_cast<Eigen::Index>(effects.size());
  if (p + q >= m) throw std::invalid_argument("linear_refit: more unknowns than residual components");
  Eigen::MatrixXd A(m, p + q);
  for (Eigen::Index c = 0; c < p; ++c) {
    if (static_cast<Eigen::Index>(jacobian[static_cast<std::size_t>(c)].size()) != m)
      throw std::invalid_argument("linear_refit: a Jacobian column has the wrong length");
    A.col(c) = to_vector(jacobian[static_cast<std::size_t>(c)]);
  }
  for (Eigen::Index c = 0; c < q; ++c) {
    if (static_cast<Eigen::Index>(effects[static_cast<std::size_t>(c)].signature.size()) != m)
      throw std::invalid_argument("linear_refit: a signature has the wrong length");
    A.col(p + c) = to_vector(effects[static_cast<std::size_t>(c)].signature);
  }
  const Eigen::VectorXd r0 = to_vector(residual);
  // Complete orthogonal decomposition: a minimum-norm answer when columns are (nearly) collinear.
  const Eigen::VectorXd x = A.completeOrthogonalDecomposition().solve(-r0);
  LinearRefit out;
  for (Eigen::Index c = 0; c < p; ++c) out.base_step.push_back(x[c]);
  for (Eigen::Index c = 0; c < q; ++c) out.effect_scale.push_back(x[p + c]);
  out.chi_square = (r0 + A * x).squaredNorm();
  return out;
}

}  // namespace shard::measure
