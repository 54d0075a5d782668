#include "shard/bending/local_deflection.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace shard::bending {

double local_deflection(std::span<const Vec3> reference, std::span<const Vec3> deformed, const SectionGauges& gauges,
                        const BendingGeometry& geometry) {
  if (reference.size() != deformed.size()) throw std::invalid_argument("local_deflection: frames differ in size");
  if (!(gauges.section_width > 0 && gauges.core_height > 0))
    throw std::invalid_argument("local_deflection: section width and core height must be positive");
  const Vec3 e = gauges.axis.normalized(), dn = gauges.down.normalized();
  const std::array<double, 4> stations{-0.5 * geometry.pin_distance, 0.5 * geometry.pin_distance, -0.5 * geometry.span,
                                       0.5 * geometry.span};
  // Per station, a least-squares line u = alpha + beta (s - station) through the band's
  // particles: alpha is the deflection at the station itself. A plain mean would be biased where
  // the band is one-sided, as over the supports 5 mm inside the beam's ends, by the slope there.
  std::array<Eigen::Matrix2d, 4> ata;
  std::array<Eigen::Vector2d, 4> atb;
  std::array<double, 4> count{};
  for (std::size_t j = 0; j < stations.size(); ++j) ata[j].setZero(), atb[j].setZero();
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const Vec3 p = reference[k] - gauges.centre;
    if (std::abs(p.dot(dn)) > 0.5 * gauges.core_height) continue;
    const double s = p.dot(e);
    const double u = (deformed[k] - reference[k]).dot(dn);
    for (std::size_t j = 0; j < stations.size(); ++j)
      if (std::abs(s - stations[j]) <= 0.5 * gauges.section_width) {
        const Eigen::Vector2d row(1.0, (s - stations[j]) / gauges.section_width);
        ata[j] += row * row.transpose();
        atb[j] += row * u;
        count[j] += 1;
      }
  }
  std::array<double, 4> at{};
  for (std::size_t j = 0; j < stations.size(); ++j) {
    if (count[j] == 0)
      throw std::invalid_argument(fmt::format("local_deflection: no particle within {:.2f} mm of s = {:+.1f} mm at "
                                              "mid-height; widen the section",
                                              0.5e3 * gauges.section_width, 1e3 * stations[j]));
    // All particles at one s (or one particle): the line is undetermined, the mean is the value.
    const Eigen::FullPivLU<Eigen::Matrix2d> lu(ata[j]);
    at[j] = lu.rank() == 2 ? lu.solve(atb[j])(0) : atb[j](0) / count[j];
  }
  const double pins = 0.5 * (at[0] + at[1]);
  const double supports = 0.5 * (at[2] + at[3]);
  return pins - supports;
}

LocalInstrumentation fit_local_instrumentation(std::vector<LocalFrame> frames, const BendingGeometry& geometry,
                                               double force_max, const CurveOptions& options) {
  LocalInstrumentation r;
  r.frames = std::move(frames);
  std::vector<double> w, f, kappa, moment;
  for (const auto& fr : r.frames)
    if (fr.force >= options.fit_low * options.window_force(force_max) &&
        fr.force <= options.fit_high * options.window_force(force_max)) {
      w.push_back(fr.deflection);
      f.push_back(fr.force);
      kappa.push_back(fr.curvature);
      moment.push_back(0.5 * fr.force * geometry.shear_span());
    }
  r.fit_frames = w.size();
  if (w.size() < 3) return r;
  const bool spread_w = std::any_of(w.begin(), w.end(), [&](double x) { return x != w.front(); });
  const bool spread_k = std::any_of(kappa.begin(), kappa.end(), [&](double x) { return x != kappa.front(); });
  if (!spread_w || !spread_k) return r;
  r.deflection_fit = fit_line(w, f);
  r.moment_fit = fit_line(kappa, moment);
  r.stiffness = r.deflection_fit.slope;
  if (r.stiffness > 0) r.youngs_modulus = youngs_modulus_from_stiffness(geometry, r.stiffness);
  if (r.moment_fit.slope > 0) r.curvature_modulus = r.moment_fit.slope / geometry.second_moment();
  r.valid = r.youngs_modulus > 0 && r.curvature_modulus > 0;
  return r;
}

double predicted_local_stiffness(const BendingGeometry& geometry, double youngs_modulus, double poisson_ratio) {
  const double shear = shear_to_bending_deflection(geometry, 2.0 * (1.0 + poisson_ratio));
  return stiffness_from_youngs_modulus(geometry, youngs_modulus) / (1.0 + shear);
}

}  // namespace shard::bending
