#include "shard/measure/comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "shard/measure/statistics.hpp"

namespace shard::measure {
namespace {

constexpr double kToeEnd = 0.10, kElasticEnd = 0.60, kPeakLevel = 0.90;  // fractions of F_max

// The rows of a curve at which the displacement reaches a new maximum: quantised or noisy
// displacement readings then give a single-valued F(w).
struct Envelope {
  std::vector<double> w, f;
  explicit Envelope(const Curve& c) {
    for (std::size_t k = 0; k < c.size(); ++k)
      if (w.empty() || c.displacement[k] > w.back()) {
        w.push_back(c.displacement[k]);
        f.push_back(c.force[k]);
      }
  }
  double at(double x) const {
    if (x <= w.front()) return f.front();
    if (x >= w.back()) return f.back();
    const auto hi = static_cast<std::size_t>(std::upper_bound(w.begin(), w.end(), x) - w.begin());
    const std::size_t lo = hi - 1;
    const double t = (x - w[lo]) / (w[hi] - w[lo]);
    return f[lo] + t * (f[hi] - f[lo]);
  }
};

std::vector<double> sample(const Curve& c, const std::vector<double>& w) {
  const Envelope e(c);
  std::vector<double> out(w.size());
  for (std::size_t k = 0; k < w.size(); ++k) out[k] = e.at(w[k]);
  return out;
}

double column_mean(const std::vector<std::vector<double>>& rows, std::size_t k, double* sd) {
  std::vector<double> v;
  for (const auto& r : rows) v.push_back(r[k]);
  if (sd) *sd = sample_sd(v);
  return mean(v);
}

// A raw score (difference over its combined uncertainty) read in the options' reference
// distribution: as it is (N(0, 1)), or as the normal score of its Student t tail (Welch).
double in_reference(double raw, double dof, const CompareOptions& options) {
  return options.score_reference == ScoreReference::Welch ? equivalent_normal_score(raw, dof) : raw;
}

void fill_regimes(Comparison& c, const CompareOptions& options) {
  const auto& f = c.measured.mean;
  const std::size_t n = f.size();
  const std::size_t peak = static_cast<std::size_t>(std::max_element(f.begin(), f.end()) - f.begin());
  const double f_max = f[peak];
  auto first_at = [&](double level) {
    std::size_t k = 0;
    while (k < peak && f[k] < level * f_max) ++k;
    return k;
  };
  const std::size_t toe_end = first_at(kToeEnd);
  const std::size_t elastic_end = std::max(toe_end, first_at(kElasticEnd));
  const std::size_t peak_start = std::max(elastic_end, first_at(kPeakLevel));
  std::size_t peak_end = peak + 1;
  while (peak_end < n && f[peak_end] >= kPeakLevel * f_max) ++peak_end;
  const std::size_t bounds[kRegimeCount + 1] = {0, toe_end, elastic_end, peak_start, peak_end, n};
  for (std::size_t r = 0; r < kRegimeCount; ++r) {
    RegimeResult& g = c.regimes[r];
    g.regime = static_cast<Regime>(r);
    g.first = bounds[r];
    g.last = bounds[r + 1];
    if (g.points() == 0) continue;
    double sum_r = 0, sum_r2 = 0, sum_sim = 0, sum_meas = 0, measured_sampled = 0, measured_known = 0, simulated = 0;
    for (std::size_t k = g.first; k < g.last; ++k) {
      measured_sampled += c.measured.sampled_variance[k];
      measured_known += c.measured.u[k] * c.measured.u[k] - c.measured.sampled_variance[k];
      simulated += c.simulated.u[k] * c.simulated.u[k];
      sum_r += c.residual[k];
      sum_r2 += c.residual[k] * c.residual[k];
      sum_sim += c.simulated.mean[k];
      sum_meas += c.measured.mean[k];
    }
    const double m = static_cast<double>(g.points());
    // The regime's variance is read as its points' mean, each part with the dof of its sample.
    const VarianceTerm estimated[] = {{measured_sampled / m, c.measured.sampled_dof},
                                      {simulated / m, c.simulated.sampled_dof}};
    g.dof = satterthwaite_dof(estimated, std::max(0.0, measured_known / m));
    g.mean_residual = in_reference(sum_r / m, g.dof, options);
    g.rms_residual = std::sqrt(sum_r2 / m);
    g.chi_square = sum_r2;
    g.relative_error = sum_meas != 0 ? (sum_sim - sum_meas) / std::abs(sum_meas) : 0;
    g.beyond_noise = std::abs(g.mean_residual) > options.noise_threshold;
  }
}

void fill_features(Comparison& c, const std::vector<Specimen>& measured, const Metadata& metadata,
                   const std::vector<Specimen>& simulated, const CompareOptions& options) {
  std::vector<FeatureValues> mv, sv;
  for (const auto& s : measured) mv.push_back(observation_features(s, metadata));
  for (const auto& s : simulated) sv.push_back(observation_features(s, metadata));
  for (std::size_t i = 0; i < kFeatureCount; ++i) {
    std::vector<double> m, s;
    double sensor2 = 0;
    for (const auto& v : mv)
      if (v.value[i]) m.push_back(*v.value[i]), sensor2 += v.sensor_uncertainty[i] * v.sensor_uncertainty[i];
    for (const auto& v : sv)
      if (v.value[i]) s.push_back(*v.value[i]);
    if (m.empty() || s.empty()) continue;
    FeatureComparison fc;
    fc.feature = feature_at(i);
    fc.measured_count = m.size();
    fc.simulated_count = s.size();
    const double nm = static_cast<double>(m.size()), ns = static_cast<double>(s.size());
    fc.measured = mean(m);
    fc.simulated = mean(s);
    const double sd_m = sample_sd(m), sd_s = sample_sd(s);
    fc.u_measured_sampled = sd_m / std::sqrt(nm);
    fc.u_measured = std::sqrt(sd_m * sd_m / nm + sensor2 / nm / nm);
    fc.u_simulated = sd_s / std::sqrt(ns);
    fc.error = fc.simulated - fc.measured;
    fc.relative_error = fc.measured != 0 ? fc.error / std::abs(fc.measured) : 0;
    fc.judged = judged_by_default(fc.feature) || (options.judge_fracture && fracture_feature(fc.feature));
    c.features.push_back(fc);
  }
}

void score_features(Comparison& c, const CompareOptions& options) {
  for (auto& fc : c.features) {
    const double u = std::hypot(fc.u_measured, fc.u_simulated);
    const VarianceTerm estimated[] = {
        {fc.u_measured_sampled * fc.u_measured_sampled, static_cast<double>(fc.measured_count) - 1},
        {fc.u_simulated * fc.u_simulated, static_cast<double>(fc.simulated_count) - 1}};
    fc.dof = satterthwaite_dof(
        estimated, std::max(0.0, fc.u_measured * fc.u_measured - fc.u_measured_sampled * fc.u_measured_sampled));
    fc.score = in_reference(u > 0 ? fc.error / u : std::numeric_limits<double>::quiet_NaN(), fc.dof, options);
    fc.beyond_noise = fc.judged && u > 0 && std::abs(fc.score) > options.noise_threshold;
  }
}

// Dynamic transients and an early first crack are reported whatever the verdict: they say how
// far F_max can be read as strength.
std::string transient_note(const Comparison& c) {
  std::string note;
  for (const auto& f : c.features) {
    if (f.feature == Feature::Oscillations && (f.measured >= 1 || f.simulated >= 1))
      note += fmt::format(" Transients: {:.1f} load oscillations after the peak per measured curve, {:.1f} per simulated "
                          "(swings above noise): a dynamic failure, where F_max may include an inertial overshoot.",
                          f.measured, f.simulated);
    if (f.feature == Feature::InitiationForce) {
      double f_max_meas = 0, f_max_sim = 0;
      for (const auto& g : c.features)
        if (g.feature == Feature::PeakForce) f_max_meas = g.measured, f_max_sim = g.simulated;
      if (f.measured < 0.95 * f_max_meas || f.simulated < 0.95 * f_max_sim)
        note += fmt::format(" First significant load drop (crack initiation) at {:.4g} N measured, {:.4g} N simulated, "
                            "before F_max ({:.4g} / {:.4g} N).",
                            f.measured, f.simulated, f_max_meas, f_max_sim);
    }
  }
  return note;
}

std::string percent(double x) { return fmt::format("{:+.1f} %", 100 * x); }

void fill_verdict(Comparison& c, const CompareOptions& options) {
  std::string failing, within, features;
  for (const auto& g : c.regimes) {
    if (g.points() == 0) continue;
    if (g.beyond_noise)
      failing += fmt::format("{}{} (force {}, mean residual {:+.1f} sigma)", failing.empty() ? "" : "; ",
                             regime_name(g.regime), percent(g.relative_error), g.mean_residual);
    else
      within += fmt::format("{}{}", within.empty() ? "" : ", ", regime_name(g.regime));
  }
  for (const auto& f : c.features)
    if (f.beyond_noise)
      features += fmt::format("{}{} {} ({:+.1f} sigma)", features.empty() ? "" : "; ", feature_name(f.feature),
                              percent(f.relative_error), f.score);
  c.adequate = failing.empty() && features.empty();
  const std::string note = transient_note(c);
  if (c.adequate) {
    double worst = 0;
    for (const auto& g : c.regimes) worst = std::max(worst, std::abs(g.mean_residual));
    c.verdict = fmt::format(
        "adequate: every regime and feature agrees within noise (largest regime mean residual {:.1f} sigma < {:.0f}; "
        "NRMSE {:.1f} %).",
        worst, options.noise_threshold, 100 * c.nrmse) + note;
    return;
  }
  c.verdict = fmt::format("The model fails beyond noise in: {}.", failing.empty() ? "no curve regime" : failing);
  if (!features.empty()) c.verdict += fmt::format(" Features beyond noise: {}.", features);
  if (!within.empty()) c.verdict += fmt::format(" Within noise: {}.", within);
  c.verdict += fmt::format(" NRMSE {:.1f} %.", 100 * c.nrmse) + note;
}

// Residual per grid point, regimes, feature scores and verdict from the bands.
void score(Comparison& c, const CompareOptions& options) {
  c.residual.clear();
  for (std::size_t k = 0; k < c.xi.size(); ++k) {
    const double u = std::hypot(c.measured.u[k], c.simulated.u[k]);
    c.residual.push_back((c.simulated.mean[k] - c.measured.mean[k]) / u);
  }
  fill_regimes(c, options);
  score_features(c, options);
  fill_verdict(c, options);
}

}  // namespace

std::string_view regime_name(Regime r) {
  switch (r) {
    case Regime::Toe: return "toe";
    case Regime::Elastic: return "elastic";
    case Regime::PrePeak: return "pre-peak";
    case Regime::Peak: return "peak";
    case Regime::PostPeak: return "post-peak";
  }
  return "?";
}

double force_at(const Curve& c, double w) { return Envelope(c).at(w); }

ScoreReference parse_score_reference(std::string_view name) {
  if (name == "normal") return ScoreReference::Normal;
  if (name == "welch") return ScoreReference::Welch;
  throw std::invalid_argument(fmt::format("score reference '{}': use normal (a score is read as N(0, 1)) or welch "
                                          "(Student t with Welch-Satterthwaite degrees of freedom, as a normal score)",
                                          name));
}

FeatureValues observation_features(const Specimen& s, const Metadata& metadata) {
  FeatureValues f = curve_features(s.curve);
  if (s.crack_position) {
    // The test is symmetric about the centre: only the distance from it is a model property.
    f[Feature::CrackPosition] = std::abs(*s.crack_position);
    f.sensor_uncertainty[static_cast<std::size_t>(Feature::CrackPosition)] = metadata.crack_position_uncertainty;
  }
  if (!s.fragment_sizes.empty()) f[Feature::FragmentX50] = fragment_x50(s.fragment_sizes, s.fragment_masses);
  if (s.fragment_count) f[Feature::FragmentCount] = *s.fragment_count;
  else if (!s.fragment_sizes.empty()) f[Feature::FragmentCount] = static_cast<double>(s.fragment_sizes.size());
  return f;
}

Comparison compare(const std::vector<Specimen>& measured, const Metadata& metadata,
                   const std::vector<Specimen>& simulated, const CompareOptions& options) {
  if (measured.empty()) throw std::invalid_argument("compare: no measured curves");
  if (simulated.empty()) throw std::invalid_argument("compare: no simulated curves");
  if (options.grid_points < 10) throw std::invalid_argument("compare: at least 10 grid points");
  Comparison c;
  c.options = options;
  std::vector<double> peaks;
  double xi_end = options.max_xi;
  for (const auto& s : measured) peaks.push_back(s.curve.displacement[peak_index(s.curve)]);
  c.reference_displacement = mean(peaks);
  if (!(c.reference_displacement > 0))
    throw std::invalid_argument("compare: the measured displacement at peak is not positive");
  for (const auto& s : measured)
    xi_end = std::min(xi_end, *std::max_element(s.curve.displacement.begin(), s.curve.displacement.end()) /
                                  c.reference_displacement);
  const std::size_t n = options.grid_points;
  std::vector<double> w(n);
  for (std::size_t k = 0; k < n; ++k) {
    c.xi.push_back(xi_end * static_cast<double>(k) / static_cast<double>(n - 1));
    w[k] = c.xi.back() * c.reference_displacement;
  }
  for (const auto& s : measured) c.measured_curves.push_back(sample(s.curve, w));
  for (const auto& s : simulated) c.simulated_curves.push_back(sample(s.curve, w));

  double uf2 = 0, uw2 = 0, count = 0;
  for (const auto& s : measured)
    for (std::size_t k = 0; k < s.curve.size(); ++k, ++count) {
      uf2 += s.curve.u_force[k] * s.curve.u_force[k];
      uw2 += s.curve.u_displacement[k] * s.curve.u_displacement[k];
    }
  uf2 /= count;
  uw2 /= count;
  const double nm = static_cast<double>(measured.size()), ns = static_cast<double>(simulated.size());
  c.measured.mean.resize(n);
  c.measured.u.resize(n);
  c.measured.sampled_variance.resize(n);
  c.measured.sampled_dof = nm - 1;
  c.simulated.sampled_dof = ns - 1;
  c.simulated.mean.resize(n);
  c.simulated.u.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    double sd_m = 0, sd_s = 0;
    c.measured.mean[k] = column_mean(c.measured_curves, k, &sd_m);
    c.simulated.mean[k] = column_mean(c.simulated_curves, k, &sd_s);
    c.simulated.u[k] = sd_s / std::sqrt(ns);
    c.measured.sampled_variance[k] = sd_m * sd_m / nm;
  }
  double sq = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k > 0 ? k - 1 : 0, b = std::min(k + 1, n - 1);
    const double slope = (c.measured.mean[b] - c.measured.mean[a]) / (w[b] - w[a]);
    c.measured.u[k] = std::sqrt(c.measured.sampled_variance[k] + (uf2 + slope * slope * uw2) / nm);
    const double diff = c.simulated.mean[k] - c.measured.mean[k];
    sq += diff * diff;
  }
  c.measured_peak_force = *std::max_element(c.measured.mean.begin(), c.measured.mean.end());
  c.nrmse = std::sqrt(sq / static_cast<double>(n)) / c.measured_peak_force;
  fill_features(c, measured, metadata, simulated, options);
  score(c, options);
  return c;
}

Comparison with_simulated_band(const Comparison& c, const Comparison& reference) {
  if (reference.xi != c.xi)
    throw std::invalid_argument("with_simulated_band: the comparisons are on different grids (other measurements)");
  Comparison out = c;
  out.simulated.u = reference.simulated.u;
  out.simulated.sampled_dof = reference.simulated.sampled_dof;
  for (auto& f : out.features) {
    f.u_simulated = 0;  // a feature the reference lacks is judged on the measured band alone
    for (const auto& g : reference.features)
      if (g.feature == f.feature) f.u_simulated = g.u_simulated;
  }
  score(out, out.options);
  return out;
}

namespace {

// Combined variance per residual-vector component, by name.
std::vector<std::pair<std::string, double>> component_variances(const Comparison& c) {
  std::vector<std::pair<std::string, double>> v;
  for (const auto& g : c.regimes)
    if (g.points() > 0) {
      double sum = 0;
      for (std::size_t k = g.first; k < g.last; ++k)
        sum += c.measured.u[k] * c.measured.u[k] + c.simulated.u[k] * c.simulated.u[k];
      v.emplace_back(fmt::format("regime:{}", regime_name(g.regime)), sum / static_cast<double>(g.points()));
    }
  for (const auto& f : c.features)
    if (f.judged && std::isfinite(f.score))
      v.emplace_back(fmt::format("feature:{}", feature_name(f.feature)),
                     f.u_measured * f.u_measured + f.u_simulated * f.u_simulated);
  return v;
}

}  // namespace

double log_variance_ratio(const Comparison& c, const Comparison& reference) {
  const auto mine = component_variances(c), theirs = component_variances(reference);
  double sum = 0;
  for (const auto& [name, v] : mine)
    for (const auto& [other, w] : theirs)
      if (name == other && v > 0 && w > 0) sum += std::log(v / w);
  return sum;
}

double Comparison::noise_nrmse() const {
  if (xi.empty() || !(measured_peak_force > 0)) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0;
  for (std::size_t k = 0; k < xi.size(); ++k) sum += measured.u[k] * measured.u[k] + simulated.u[k] * simulated.u[k];
  return std::sqrt(sum / static_cast<double>(xi.size())) / measured_peak_force;
}

ResidualVector Comparison::residual_vector() const {
  ResidualVector v;
  for (const auto& g : regimes)
    if (g.points() > 0) {
      v.names.push_back(fmt::format("regime:{}", regime_name(g.regime)));
      v.values.push_back(g.mean_residual);
    }
  for (const auto& f : features)
    if (f.judged && std::isfinite(f.score)) {
      v.names.push_back(fmt::format("feature:{}", feature_name(f.feature)));
      v.values.push_back(f.score);
    }
  return v;
}

}  // namespace shard::measure
