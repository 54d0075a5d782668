#include "shard/analysis/deformation_kinetic.hpp"

#include <Eigen/Dense>

#include <algorithm>

namespace shard::analysis {

double deformation_kinetic_energy(const Particles& p) {
  const std::size_t n = p.size();
  if (n < 2) return 0;
  double m_total = 0, total = 0;
  Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    m_total += p.mass[k];
    centre += p.mass[k] * p.position[k];
    momentum += p.mass[k] * p.velocity[k];
    total += 0.5 * (p.mass[k] * p.velocity[k].squaredNorm() + p.inertia[k] * p.omega[k].squaredNorm());
  }
  if (!(m_total > 0)) return 0;
  centre /= m_total;
  const Vec3 v_centre = momentum / m_total;
  // Angular momentum about the centre of mass (orbital in the centre-of-mass frame plus spins)
  // and the inertia tensor of the particles (parallel-axis terms plus their own spheres').
  Vec3 angular = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 r = p.position[k] - centre;
    angular += p.mass[k] * r.cross(p.velocity[k] - v_centre) + p.inertia[k] * p.omega[k];
    inertia += p.mass[k] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose()) + p.inertia[k] * Mat3::Identity();
  }
  // J is symmetric positive definite for any two particles with spin inertia; LDLT is safe for
  // a collinear pair too (the spins keep it definite).
  const Vec3 omega = inertia.ldlt().solve(angular);
  const double rigid = 0.5 * m_total * v_centre.squaredNorm() + 0.5 * omega.dot(angular);
  return std::max(0.0, total - rigid);
}

}  // namespace shard::analysis
