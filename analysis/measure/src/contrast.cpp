#include "shard/measure/contrast.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "shard/measure/comparison.hpp"
#include "shard/measure/features.hpp"
#include "shard/measure/statistics.hpp"
#include "square_matrix.hpp"

namespace shard::measure {
namespace {

// The force after the peak falls below this share of F_max where the beam has parted: the
// ductility component reads how far past the peak that happens.
constexpr double kPartedShare = 0.5;

// The stiffness band in shares of the reference's F_max (StiffnessBand): above the seating toe,
// and its top below 60 % of the peak (the own-window's top) of a batch down to 0.4 / 0.6 of the
// reference's strength; a weaker specimen's band is scaled down to that 60 % of its own peak.
constexpr double kBandLow = 0.10, kBandHigh = 0.40, kWeakBatchTop = 0.60;

Eigen::VectorXd to_vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

double positive_log(double x, const char* what, const Curve& c) {
  if (!(x > 0)) throw CurveWithoutRise(c.id, what, x);
  return std::log(x);
}

double quadratic_chi_square(const Eigen::VectorXd& d, const Eigen::MatrixXd& w, const Eigen::VectorXd& model) {
  const Eigen::VectorXd r = d - model;
  return r.dot(w * r);
}

// The remainder with the form tolerance of the model's contrast on the diagonal.
double form_chi_square(const Eigen::VectorXd& d, const Eigen::MatrixXd& w, const Eigen::VectorXd& model,
                       double tolerance) {
  Eigen::MatrixXd c = w.llt().solve(Eigen::MatrixXd::Identity(w.rows(), w.cols()));
  for (Eigen::Index i = 0; i < d.size(); ++i) c(i, i) += std::pow(tolerance * model(i), 2);
  const Eigen::VectorXd r = d - model;
  return r.dot(c.llt().solve(r));
}

// The estimate's components not yet fitted once `fitted` directions are taken out.
double unfitted(const ScatterEstimate& noise, double fitted) { return std::max(1.0, noise.dimension - fitted); }

// A remainder's p: Hotelling's test of the components left once `fitted` directions are taken
// out, of the contrast's m and of the estimate's p alike.
double remainder_p(double chi_square, double m, const ScatterEstimate& noise, double fitted) {
  return hotelling_p(chi_square, std::max(1.0, m - fitted), noise.dof, unfitted(noise, fitted));
}

void judge_pair(ContrastPairFit& p, const Eigen::VectorXd& d, const Eigen::MatrixXd& w, const Eigen::VectorXd& model,
                double first_chi_square, const ScatterEstimate& noise, const ContrastOptions& options) {
  const auto m = static_cast<double>(d.size());
  p.chi_square = quadratic_chi_square(d, w, model);
  p.drop = first_chi_square - p.chi_square;
  p.p_drop = added_direction_p(p.drop, p.chi_square, noise.dof, unfitted(noise, 1));
  p.chi_square_form = form_chi_square(d, w, model, options.form_tolerance);
  p.p_after = remainder_p(p.chi_square_form, m, noise, 2);
}

}  // namespace

CurveWithoutRise::CurveWithoutRise(std::string curve_, std::string figure_, double value_)
    : std::invalid_argument(fmt::format("curve '{}': {} is {:g}, not positive: the curve has no rise to a peak "
                                        "(check the sign convention: force and displacement positive into the "
                                        "specimen)",
                                        curve_, figure_, value_)),
      curve(std::move(curve_)),
      figure(std::move(figure_)),
      value(value_) {}

std::string simulated_without_rise(const CurveWithoutRise& e, double rate) {
  return fmt::format("at {:g} mm/s the simulated curve '{}' has no rise to a peak ({} {:.4g}): the beam was not bent "
                     "up to a fracture (it slid on its supports, or inertia carried the load), so the run gives no "
                     "contrast",
                     rate * 1e3, e.curve, e.figure, e.value);
}

ContrastScale contrast_scale(const std::vector<Curve>& curves) {
  if (curves.empty()) throw std::invalid_argument("contrast: no curves to take the scale from");
  ContrastScale s;
  for (const auto& c : curves) {
    const std::size_t p = peak_index(c);
    s.w_ref += c.displacement[p];
    s.f_ref += c.force[p];
  }
  s.w_ref /= static_cast<double>(curves.size());
  s.f_ref /= static_cast<double>(curves.size());
  return s;
}

const std::vector<std::string>& contrast_component_names() {
  static const std::vector<std::string> names = {
      "ln_stiffness", "ln_peak_force", "ln_peak_displacement", "ln_work_to_peak",
      "nonlinearity", "ductility",    "ln_initiation_force", "ln_initiation_displacement",
  };
  return names;
}

StiffnessBand stiffness_band(const ContrastScale& reference) {
  return {kBandLow * reference.f_ref, kBandHigh * reference.f_ref};
}

namespace {

ElasticFit contrast_line(const Curve& c, double f_max, const StiffnessBand& band) {
  if (!(band.high > 0)) return elastic_fit(c);
  const double high = std::min(band.high, kWeakBatchTop * f_max);
  return elastic_fit_between(c, band.low * high / band.high, high);
}

}  // namespace

std::vector<double> contrast_components(const Curve& c, const StiffnessBand& band) {
  const std::size_t p = peak_index(c);
  const FeatureValues f = curve_features(c);
  const CrackInitiation initiation = crack_initiation(c);
  const double f_max = c.force[p];
  const double w_peak = c.displacement[p];
  const ElasticFit line = contrast_line(c, f_max, band);
  double w_parted = c.displacement.back();
  for (std::size_t k = p; k < c.size(); ++k)
    if (c.force[k] < kPartedShare * f_max) {
      w_parted = c.displacement[k];
      break;
    }
  return {
      positive_log(line.stiffness, "the stiffness", c),
      positive_log(f_max, "the peak force", c),
      positive_log(w_peak, "the displacement at peak", c),
      positive_log(*f[Feature::WorkToPeak], "the work to peak", c),
      line.nonlinearity(f_max, w_peak),
      positive_log(w_parted / w_peak, "the parting-to-peak displacement ratio", c),
      positive_log(initiation.force, "the force at crack initiation", c),
      positive_log(initiation.displacement, "the displacement at crack initiation", c),
  };
}

std::vector<double> component_mean(const std::vector<std::vector<double>>& rows) {
  if (rows.empty()) throw std::invalid_argument("contrast: mean of no rows");
  std::vector<double> m(rows.front().size(), 0.0);
  for (const auto& r : rows)
    for (std::size_t i = 0; i < m.size(); ++i) m[i] += r[i] / static_cast<double>(rows.size());
  return m;
}

std::vector<double> median_of(const std::vector<std::vector<double>>& rows) {
  std::vector<double> out(rows.front().size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::vector<double> v;
    for (const auto& r : rows) v.push_back(r[i]);
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    out[i] = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  }
  return out;
}

std::vector<std::vector<double>> pooled_covariance(const std::vector<std::vector<std::vector<double>>>& groups,
                                                   double shrinkage, double& dof) {
  std::size_t m = 0;
  for (const auto& g : groups)
    if (!g.empty()) m = g.front().size();
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  dof = 0;
  for (const auto& g : groups) {
    if (g.size() < 2) continue;
    const Eigen::VectorXd mean = to_vector(component_mean(g));
    for (const auto& row : g) {
      const Eigen::VectorXd d = to_vector(row) - mean;
      s += d * d.transpose();
    }
    dof += static_cast<double>(g.size() - 1);
  }
  if (dof < 1) throw std::invalid_argument("contrast: no set has two specimens, so their scatter is unknown");
  s /= dof;
  // Shrinking the off-diagonal terms keeps the matrix invertible and well conditioned when the
  // specimens are few against the components (Ledoit-Wolf's target, a fixed intensity).
  for (Eigen::Index i = 0; i < s.rows(); ++i)
    for (Eigen::Index j = 0; j < s.cols(); ++j)
      if (i != j) s(i, j) *= 1 - shrinkage;
  return from_matrix(s);
}

double hotelling_p(double t_square, double k, double nu, double p) {
  if (!(t_square > 0)) return 1;
  const double d2 = nu - p + 1;
  if (d2 < 1) return chi_square_survival(t_square, k);
  const boost::math::fisher_f_distribution<double> f(k, d2);
  return boost::math::cdf(boost::math::complement(f, d2 / (nu * k) * t_square));
}

double hotelling_critical(double level, double k, double nu, double p) {
  const double d2 = nu - p + 1;
  if (d2 < 1) return chi_square_critical(level, k);
  const boost::math::fisher_f_distribution<double> f(k, d2);
  return nu * k / d2 * boost::math::quantile(boost::math::complement(f, level));
}

double added_direction_p(double drop, double after, double nu, double p) {
  if (!(drop > 0)) return 1;
  const double d2 = nu - p + 1;
  if (d2 < 1) return chi_square_survival(drop, 1);
  const boost::math::fisher_f_distribution<double> f(1, d2);
  return boost::math::cdf(boost::math::complement(f, d2 * drop / (nu + std::max(0.0, after))));
}

std::vector<std::vector<double>> spd_inverse(const std::vector<std::vector<double>>& a) {
  const Eigen::MatrixXd m = to_matrix(a);
  const Eigen::LLT<Eigen::MatrixXd> llt(m);
  if (llt.info() != Eigen::Success)
    throw std::invalid_argument("contrast: the covariance of the components is not positive definite (identical "
                                "specimens or a constant component)");
  return from_matrix(llt.solve(Eigen::MatrixXd::Identity(m.rows(), m.cols())));
}

ContrastDecision decide_contrast(const std::vector<double>& difference, const std::vector<std::vector<double>>& weight,
                                 const std::vector<EffectSignature>& effects, const ScatterEstimate& noise,
                                 const ContrastOptions& options) {
  const Eigen::VectorXd d = to_vector(difference);
  const Eigen::MatrixXd w = to_matrix(weight);
  if (w.rows() != d.size()) throw std::invalid_argument("contrast: weight and difference differ in size");
  const auto m = static_cast<double>(d.size());
  ContrastDecision out;
  out.chi_square = d.dot(w * d);
  out.p_value = hotelling_p(out.chi_square, m, noise.dof, noise.dimension);
  for (const auto& e : effects) {
    if (e.signature.size() != difference.size())
      throw std::invalid_argument(fmt::format("contrast: the signature of '{}' has the wrong length", e.name));
    const Eigen::VectorXd t = to_vector(e.signature);
    const double tt = t.dot(w * t), td = t.dot(w * d);
    ContrastFit fit;
    fit.name = e.name;
    fit.identifiable = e.identifiable;
    const double raw = tt > 0 ? td / tt : 0.0;
    fit.scale = std::clamp(raw, e.scale_min, e.scale_max);
    fit.at_bound = fit.scale != raw;
    fit.u_scale = tt > 0 ? 1 / std::sqrt(tt) : std::numeric_limits<double>::infinity();
    fit.chi_square = out.chi_square - 2 * fit.scale * td + fit.scale * fit.scale * tt;
    fit.drop = out.chi_square - fit.chi_square;
    // The weight is estimated from the specimens' scatter, and its error enters the drop as well
    // as the remainder: Rao's test weighs the one by the other.
    fit.p_drop = added_direction_p(fit.drop, fit.chi_square, noise.dof, unfitted(noise, 0));
    // The remainder judged with the effect's form tolerance (ContrastOptions::form_tolerance).
    fit.chi_square_form = form_chi_square(d, w, fit.scale * t, options.form_tolerance);
    fit.p_after = remainder_p(fit.chi_square_form, m, noise, 1);
    out.fits.push_back(fit);
  }
  std::sort(out.fits.begin(), out.fits.end(), [](const auto& a, const auto& b) { return a.chi_square < b.chi_square; });
  const double n = static_cast<double>(std::max<std::size_t>(1, options.tried > 0 ? options.tried : effects.size()));
  double best_p_drop = 1;
  for (const auto& f : out.fits) best_p_drop = std::min(best_p_drop, f.p_drop);
  if (out.p_value > options.no_difference_p && best_p_drop >= options.significant_p / n) {
    out.verdict = kNoDifference;
    return out;
  }
  const ContrastFit* named = nullptr;
  for (const auto& f : out.fits)
    if (f.scale != 0 && f.p_drop < options.drop_p / n && f.p_after > options.remaining_p) {
      if (!f.identifiable) {
        if (out.unidentifiable.empty()) out.unidentifiable = f.name;
        continue;
      }
      named = &f;
      break;
    }
  if (!named) {
    out.verdict = out.p_value > options.no_difference_p ? kNoDifference : kUnexplainedDifference;
    return out;
  }
  out.verdict = named->name;
  out.unidentifiable.clear();  // a better fit that cannot be named is a rival (below)
  out.rivals = rivals_of(out.fits, *named, options.drop_p / n, options);
  return out;
}

std::vector<std::string> rivals_of(const std::vector<ContrastFit>& fits, const ContrastFit& named, double level,
                                   const ContrastOptions& options) {
  std::vector<std::string> rivals;
  for (const auto& f : fits)
    if (&f != &named && f.scale != 0 && f.p_drop < level && f.chi_square - named.chi_square < options.rival_chi_square)
      rivals.push_back(f.name);
  return rivals;
}

}  // namespace shard::measure

namespace shard::measure {

ContrastPairFit fit_contrast_pair(const std::vector<double>& difference, const std::vector<std::vector<double>>& weight,
                                  const EffectSignature& first, const EffectSignature& second, double first_chi_square,
                                  const ScatterEstimate& noise, const ContrastOptions& options) {
  const Eigen::VectorXd d = to_vector(difference), t1 = to_vector(first.signature), t2 = to_vector(second.signature);
  const Eigen::MatrixXd w = to_matrix(weight);
  if (t1.size() != d.size() || t2.size() != d.size())
    throw std::invalid_argument(fmt::format("contrast: the signature of '{}' or '{}' has the wrong length", first.name,
                                            second.name));
  Eigen::Matrix2d a;
  a << t1.dot(w * t1), t1.dot(w * t2), t1.dot(w * t2), t2.dot(w * t2);
  const Eigen::Vector2d rhs(t1.dot(w * d), t2.dot(w * d));
  ContrastPairFit p;
  p.first = first.name;
  p.second = second.name;
  // Candidates: the free optimum, then each size held at one of its finite bounds with the other
  // refit, then both at bounds; the best admissible one is the constrained optimum (a convex
  // quadratic over a box: its minimum is the free one or lies on the box's faces).
  auto admissible = [&](double x, double y) {
    return x >= first.scale_min && x <= first.scale_max && y >= second.scale_min && y <= second.scale_max;
  };
  std::vector<std::pair<double, double>> candidates;
  const Eigen::FullPivLU<Eigen::Matrix2d> lu(a);
  if (lu.isInvertible()) {
    const Eigen::Vector2d x = lu.solve(rhs);
    candidates.emplace_back(x(0), x(1));
  }
  const double bounds1[] = {first.scale_min, first.scale_max}, bounds2[] = {second.scale_min, second.scale_max};
  for (double x : bounds1)
    if (std::isfinite(x) && a(1, 1) > 0) candidates.emplace_back(x, std::clamp((rhs(1) - a(0, 1) * x) / a(1, 1), second.scale_min, second.scale_max));
  for (double y : bounds2)
    if (std::isfinite(y) && a(0, 0) > 0) candidates.emplace_back(std::clamp((rhs(0) - a(0, 1) * y) / a(0, 0), first.scale_min, first.scale_max), y);
  for (double x : bounds1)
    for (double y : bounds2)
      if (std::isfinite(x) && std::isfinite(y)) candidates.emplace_back(x, y);
  double best = std::numeric_limits<double>::infinity();
  bool free_optimum = false;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const auto [x, y] = candidates[k];
    if (!admissible(x, y)) continue;
    const double c = quadratic_chi_square(d, w, x * t1 + y * t2);
    if (c < best) {
      best = c;
      p.scale_first = x;
      p.scale_second = y;
      free_optimum = k == 0 && lu.isInvertible();
    }
  }
  if (!std::isfinite(best)) {  // nothing admissible: the first alone at its single size
    p.scale_first = std::clamp(rhs(0) / a(0, 0), first.scale_min, first.scale_max);
    p.scale_second = 0;
  }
  p.at_bound = !free_optimum;
  if (lu.isInvertible()) {
    const Eigen::Matrix2d inv = lu.inverse();
    p.u_scale_first = std::sqrt(std::max(0.0, inv(0, 0)));
    p.u_scale_second = std::sqrt(std::max(0.0, inv(1, 1)));
  } else {
    p.u_scale_first = p.u_scale_second = std::numeric_limits<double>::infinity();
  }
  judge_pair(p, d, w, p.scale_first * t1 + p.scale_second * t2, first_chi_square, noise, options);
  return p;
}

ContrastPairFit judge_simulated_pair(const std::vector<double>& difference,
                                     const std::vector<std::vector<double>>& weight, const std::vector<double>& combined,
                                     ContrastPairFit sized, double first_chi_square, const ScatterEstimate& noise,
                                     const ContrastOptions& options) {
  if (combined.size() != difference.size())
    throw std::invalid_argument("contrast: the pair's simulated contrast has the wrong length");
  judge_pair(sized, to_vector(difference), to_matrix(weight), to_vector(combined), first_chi_square, noise, options);
  return sized;
}

namespace {

// Each seed's move projected on the residual by `product`, tested by mean_above_zero_p.
template <class Product>
double moves_along_residual_p(const std::vector<double>& residual, const std::vector<std::vector<double>>& moves,
                              Product product) {
  std::vector<double> along;
  for (const auto& move : moves) {
    if (move.size() != residual.size()) throw std::invalid_argument("contrast: a seed's move has the wrong length");
    along.push_back(product(move));
  }
  return mean_above_zero_p(along);
}

}  // namespace

double seed_consistency_p(const std::vector<double>& residual, const std::vector<std::vector<double>>& weight,
                          const std::vector<std::vector<double>>& moves) {
  return moves_along_residual_p(residual, moves, [&](const std::vector<double>& move) {
    double g = 0;
    for (std::size_t i = 0; i < residual.size(); ++i)
      for (std::size_t j = 0; j < residual.size(); ++j) g += residual[i] * weight[i][j] * move[j];
    return g;
  });
}

double seed_consistency_p(const std::vector<double>& residual, const std::vector<std::vector<double>>& moves) {
  return moves_along_residual_p(residual, moves, [&](const std::vector<double>& move) {
    double g = 0;
    for (std::size_t i = 0; i < residual.size(); ++i) g += residual[i] * move[i];
    return g;
  });
}

bool starts_a_pair(const ContrastFit& closest, double t_square, std::size_t effects, const ContrastOptions& options) {
  const double n = static_cast<double>(std::max<std::size_t>(1, effects));
  return closest.p_drop < options.drop_p / n && closest.identifiable && closest.drop >= options.pair_first_share * t_square;
}

bool pair_is_named(const ContrastPairFit& pair, std::size_t seconds_tried, const ContrastOptions& options) {
  const double n = static_cast<double>(std::max<std::size_t>(1, seconds_tried));
  return pair.scale_second != 0 && pair.p_drop < options.drop_p / n && pair.p_after > options.remaining_p &&
         pair.p_seeds < options.drop_p;
}

}  // namespace shard::measure
