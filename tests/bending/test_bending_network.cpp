// Crack location, the network's Voigt modulus and the curvature modulus on cases with known answers.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "shard/bending/crack_location.hpp"
#include "shard/bending/network_stiffness.hpp"

using namespace shard;
using namespace shard::bending;

TEST_CASE("crack: the densest cluster of breaks wins over scattered damage") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> anywhere(-0.09, 0.09), across(-0.015, 0.015);
  std::normal_distribution<double> crack(0.012, 0.0015);
  std::vector<Vec3> mids;
  for (int k = 0; k < 60; ++k) mids.emplace_back(anywhere(rng), across(rng), 0.01);  // diffuse damage
  for (int k = 0; k < 60; ++k) mids.emplace_back(crack(rng), across(rng), 0.02);     // the crack at +12 mm
  const auto c = locate_crack(mids, Vec3(0, 0, 0.0175), Vec3::UnitX(), 0.006, 0.080);
  REQUIRE(c.found);
  CHECK(c.breaks == 120);
  CHECK(c.cluster_breaks >= 40);  // ~95 % of the crack's breaks lie within +-3 mm = 2 sigma
  CHECK(std::abs(c.position - 0.012) < 0.0015);
  CHECK(c.between_pins);
  // The same crack at 60 mm lies outside pins 80 mm apart.
  for (auto& m : mids) m.x() += 0.048;
  const auto outside = locate_crack(mids, Vec3(0, 0, 0.0175), Vec3::UnitX(), 0.006, 0.080);
  CHECK(std::abs(outside.position - 0.060) < 0.0015);
  CHECK_FALSE(outside.between_pins);
  CHECK_FALSE(locate_crack({}, Vec3::Zero(), Vec3::UnitX(), 0.006, 0.08).found);
}

namespace {

struct Lattice {
  std::vector<Vec3> x;
  std::vector<double> r;
  std::vector<Index> bi, bj;
  double volume = 0;
};

// A simple cubic lattice of spheres of radius r touching along x, y and z, bonded to their six
// neighbours; volume = n^3 cells of (2r)^3.
Lattice cubic(int nx, int ny, int nz, double r) {
  Lattice l;
  auto id = [&](int i, int j, int k) { return static_cast<Index>((i * ny + j) * nz + k); };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        l.x.emplace_back(2 * r * i, 2 * r * j, 2 * r * k);
        l.r.push_back(r);
        if (i + 1 < nx) l.bi.push_back(id(i, j, k)), l.bj.push_back(id(i + 1, j, k));
        if (j + 1 < ny) l.bi.push_back(id(i, j, k)), l.bj.push_back(id(i, j + 1, k));
        if (k + 1 < nz) l.bi.push_back(id(i, j, k)), l.bj.push_back(id(i, j, k + 1));
      }
  l.volume = (2 * r * nx) * (2 * r * ny) * (2 * r * nz);
  return l;
}

}  // namespace

TEST_CASE("Voigt modulus of a simple cubic lattice along an axis is pi/4 lambda^2 E_b with nu = 0") {
  // Per cell (2r)^3 one x-bond k_n = E_b pi r_b^2 / (2r) carries the stress: E = k_n 2r / (2r)^2.
  // The lattice is periodic in spirit: bonds missing at the faces make the finite sample softer
  // by (n-1)/n along the axis, so the expected value carries that factor.
  const int n = 12;
  const auto l = cubic(n, n, n, 0.5e-3);
  BeamBondParameters p;
  p.youngs_modulus = 12.8e6;
  const double edge = static_cast<double>(n - 1) / n;
  for (double lambda : {1.0, 0.6}) {
    p.radius_ratio = lambda;
    const auto v = voigt_modulus(l.x, l.r, l.bi, l.bj, p, l.volume, Vec3::UnitX());
    CHECK(v.youngs_modulus == doctest::Approx(std::numbers::pi / 4 * lambda * lambda * 12.8e6 * edge).epsilon(1e-9));
    CHECK(std::abs(v.poisson_ratio) < 1e-12);
    // The same along y and z (cubic symmetry).
    CHECK(voigt_modulus(l.x, l.r, l.bi, l.bj, p, l.volume, Vec3::UnitY()).youngs_modulus ==
          doctest::Approx(v.youngs_modulus).epsilon(1e-9));
  }
  // Along the cube diagonal the shear springs carry load: softer than along the axis (for a_s G_b < E_b).
  p.radius_ratio = 1.0;
  const double diag = voigt_modulus(l.x, l.r, l.bi, l.bj, p, l.volume, Vec3(1, 1, 1)).youngs_modulus;
  CHECK(diag < voigt_modulus(l.x, l.r, l.bi, l.bj, p, l.volume, Vec3::UnitX()).youngs_modulus);
  CHECK(diag > 0);
}

TEST_CASE("Voigt modulus of a random isotropic network matches the closed form for isotropic fabric") {
  // For bond directions uniform on the sphere (all of length l, same k_n, k_t), the affine
  // moduli are E = (N l^2 / 3V) k_n (2 k_n + 3 k_t) / (4 k_n + k_t), nu = (k_n - k_t) / (4 k_n + k_t).
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss;
  const double r = 1e-3, l = 2 * r;
  const int bonds = 200000;
  std::vector<Vec3> x;
  std::vector<double> rad;
  std::vector<Index> bi, bj;
  for (int b = 0; b < bonds; ++b) {
    Vec3 n(gauss(rng), gauss(rng), gauss(rng));
    n.normalize();
    x.push_back(Vec3::Zero());
    x.push_back(l * n);
    rad.push_back(r), rad.push_back(r);
    bi.push_back(2 * b), bj.push_back(2 * b + 1);
  }
  BeamBondParameters p;
  const double volume = 1.0;
  const auto v = voigt_modulus(x, rad, bi, bj, p, volume, Vec3::UnitX());
  const double area = std::numbers::pi * r * r;
  const double kn = p.youngs_modulus * area / l, kt = p.shear_coefficient * p.effective_shear_modulus() * area / l;
  const double e = bonds * l * l / (3 * volume) * kn * (2 * kn + 3 * kt) / (4 * kn + kt);
  // Sampling 2e5 directions: the fabric's anisotropy is O(1/sqrt(N)) ~ 0.2 %.
  CHECK(v.youngs_modulus == doctest::Approx(e).epsilon(0.01));
  CHECK(v.poisson_ratio == doctest::Approx((kn - kt) / (4 * kn + kt)).epsilon(0.02).scale(0));
}

TEST_CASE("curvature modulus recovers E from a pure-bending field plus rigid motion") {
  const BendingGeometry g{0.170, 0.080, 0.030, 0.035};
  const double e = 9.5e6, force = 40.0;
  const double m = 0.5 * force * g.shear_span();
  const double kappa = m / (e * g.second_moment());
  std::vector<Vec3> ref, def;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(-0.09, 0.09), uy(-0.015, 0.015), uz(0.0, 0.035);
  for (int k = 0; k < 4000; ++k) {
    const Vec3 p(ux(rng), uy(rng), uz(rng));
    ref.push_back(p);
    // Deflection downwards (-z), largest at the centre: u = kappa/2 (c^2 - s^2), plus a rigid
    // drop of 0.2 mm and a small tilt.
    const double s = p.x();
    const double sag = 0.5 * kappa * (0.04 * 0.04 - s * s);
    def.push_back(p + Vec3(0, 0, -sag - 2e-4 - 1e-3 * s));
  }
  const auto c = curvature_modulus(ref, def, Vec3(0, 0, 0.0175), Vec3::UnitX(), -Vec3::UnitZ(), g, force);
  REQUIRE(c.valid);
  CHECK(c.youngs_modulus == doctest::Approx(e).epsilon(1e-9));
  CHECK(c.r_squared == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(c.particles > 1000);
}
