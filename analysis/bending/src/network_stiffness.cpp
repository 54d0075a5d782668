#include "shard/bending/network_stiffness.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shard::bending {
namespace {

// Strain tensor of the Voigt basis vector a (engineering shears: gamma_xy = 2 eps_xy).
Eigen::Matrix3d voigt_basis(int a) {
  Eigen::Matrix3d e = Eigen::Matrix3d::Zero();
  static constexpr std::array<std::array<int, 2>, 6> ij{{{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
  const auto [i, j] = ij[static_cast<std::size_t>(a)];
  if (i == j) {
    e(i, j) = 1;
  } else {
    e(i, j) = 0.5;
    e(j, i) = 0.5;
  }
  return e;
}

// Rotation taking `axis` onto x, so the modulus along the axis is the xx compliance.
Eigen::Matrix3d frame_with_x_along(const Vec3& axis) {
  const Vec3 x = axis.normalized();
  const Vec3 helper = std::abs(x.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 y = (helper - helper.dot(x) * x).normalized();
  const Vec3 z = x.cross(y);
  Eigen::Matrix3d r;
  r.row(0) = x.transpose();
  r.row(1) = y.transpose();
  r.row(2) = z.transpose();
  return r;
}

}  // namespace

VoigtEstimate voigt_modulus(std::span<const Vec3> position, std::span<const double> radius,
                            std::span<const Index> bond_i, std::span<const Index> bond_j,
                            const BeamBondParameters& bond, double volume, const Vec3& axis) {
  if (position.size() != radius.size() || bond_i.size() != bond_j.size())
    throw std::invalid_argument("voigt_modulus: array lengths differ");
  if (!(volume > 0)) throw std::invalid_argument("voigt_modulus: the volume must be positive");
  const Eigen::Matrix3d rot = frame_with_x_along(axis);
  std::array<Eigen::Matrix3d, 6> basis;
  for (int a = 0; a < 6; ++a) basis[static_cast<std::size_t>(a)] = voigt_basis(a);
  const double e_b = bond.youngs_modulus, g_b = bond.effective_shear_modulus();
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t b = 0; b < bond_i.size(); ++b) {
    const auto i = static_cast<std::size_t>(bond_i[b]), j = static_cast<std::size_t>(bond_j[b]);
    if (i >= position.size() || j >= position.size()) throw std::invalid_argument("voigt_modulus: bond index out of range");
    const Vec3 d = rot * (position[j] - position[i]);
    const double l = d.norm();
    if (!(l > 0)) continue;
    const Vec3 n = d / l;
    const double rb = bond.radius_ratio * std::min(radius[i], radius[j]);
    const double area = std::numbers::pi * rb * rb;
    const double kn = e_b * area / l, kt = bond.shear_coefficient * g_b * area / l;
    std::array<Vec3, 6> g;
    std::array<double, 6> gn;
    for (std::size_t a = 0; a < 6; ++a) {
      g[a] = basis[a] * n;
      gn[a] = n.dot(g[a]);
    }
    for (std::size_t a = 0; a < 6; ++a)
      for (std::size_t bb = 0; bb < 6; ++bb)
        c(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(bb)) +=
            l * l * ((kn - kt) * gn[a] * gn[bb] + kt * g[a].dot(g[bb]));
  }
  c /= volume;
  VoigtEstimate v;
  v.bonds = bond_i.size();
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(c);
  if (!lu.isInvertible()) throw std::invalid_argument("voigt_modulus: the bond network has a zero-stiffness mode");
  const Eigen::Matrix<double, 6, 6> s = lu.inverse();
  v.youngs_modulus = 1.0 / s(0, 0);
  v.poisson_ratio = -0.5 * (s(1, 0) + s(2, 0)) / s(0, 0);
  return v;
}

CurvatureModulus curvature_modulus(std::span<const Vec3> reference, std::span<const Vec3> deformed,
                                   const Vec3& centre, const Vec3& axis, const Vec3& down,
                                   const BendingGeometry& geometry, double force, double zone_fraction) {
  if (reference.size() != deformed.size()) throw std::invalid_argument("curvature_modulus: frames differ in size");
  const Vec3 e = axis.normalized(), dn = down.normalized();
  const double half = zone_fraction * 0.5 * geometry.pin_distance;
  // Least squares for u(s) = c0 + c1 s + c2 s^2 (u: displacement along `down`), s scaled by
  // `half` so the normal equations stay well conditioned.
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  double sum_u = 0, sum_uu = 0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const double s = (reference[k] - centre).dot(e);
    if (std::abs(s) > half) continue;
    const double u = (deformed[k] - reference[k]).dot(dn);
    const double t = s / half;
    const Eigen::Vector3d row(1.0, t, t * t);
    ata += row * row.transpose();
    atb += row * u;
    sum_u += u;
    sum_uu += u * u;
    ++n;
  }
  CurvatureModulus m;
  m.particles = n;
  m.force = force;
  m.moment = 0.5 * force * geometry.shear_span();
  if (n < 10) return m;
  const Eigen::Vector3d coef = ata.ldlt().solve(atb);
  const double c2 = coef(2) / (half * half);
  // Deflection along `down` is largest at the centre: u is concave, d2u/ds2 = 2 c2 < 0.
  m.curvature = -2.0 * c2;
  const double ss_tot = sum_uu - sum_u * sum_u / static_cast<double>(n);
  const double ss_res = sum_uu - coef.dot(atb);
  m.r_squared = ss_tot > 0 ? 1.0 - ss_res / ss_tot : 0.0;
  if (m.curvature > 0 && force > 0) {
    m.youngs_modulus = m.moment / (m.curvature * geometry.second_moment());
    m.valid = true;
  }
  return m;
}

}  // namespace shard::bending
