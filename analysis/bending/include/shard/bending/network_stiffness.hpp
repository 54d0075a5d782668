#pragma once
// The bonded network's own Young's modulus, two ways, to set beside eq. 14.
//
// 1. Voigt (affine) estimate from the bonds. Every bond is a normal spring k_n = E_b A_b / l and a
//    shear spring k_t = a_s G_b A_b / l (eq. 3 with the particles not rotating). A uniform strain
//    eps stretches bond l n by l eps n, so the strain energy density is
//      W = 1/(2V) sum l^2 [ k_n (n.eps.n)^2 + k_t (|eps n|^2 - (n.eps.n)^2) ]
//    and C_ab = d2W/deps_a deps_b (Voigt 6-vector, engineering shears). The modulus along the
//    beam axis is 1 / (C^-1)_xx. Affine motion is an upper bound: particle rotations and
//    non-affine relaxation only lower it. It is exact for a simple cubic lattice loaded along a
//    lattice axis (pi/4 lambda^2 E_b, no Poisson coupling), the check used in the tests.
// 2. Local instrumentation: between the pins the bending moment is constant, M = F a / 2, so the
//    deflection line is a parabola w(s) = c0 + c1 s + c2 s^2 with curvature 2 c2 = M / (E I).
//    Fitting the particles' vertical displacement between two frames over the inner part of the
//    constant-moment zone gives E = M / (2 c2 I) free of the pins' indentation and of the shear
//    deflection of the outer spans, the two things eq. 14 lumps into E.
#include <cstddef>
#include <span>

#include "shard/bending/beam_theory.hpp"
#include "shard/types.hpp"

namespace shard::bending {

struct BeamBondParameters {
  double youngs_modulus = 12.8e6;   // E_b, Pa
  double shear_modulus = 0;         // G_b, Pa; 0: E_b / (2 (1 + nu_b))
  double poisson_ratio = 0.25;      // nu_b
  double shear_coefficient = 0.9;   // a_s
  double radius_ratio = 1.0;        // lambda
  double critical_stress = 0.24e6;  // Pa
  bool breakage = true;
  double effective_shear_modulus() const {
    return shear_modulus > 0 ? shear_modulus : youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  }
};

struct VoigtEstimate {
  double youngs_modulus = 0;  // along `axis`, Pa
  double poisson_ratio = 0;   // -eps_lateral / eps_axis under uniaxial stress along axis (mean of the two)
  std::size_t bonds = 0;
};

// bond_i/bond_j index positions/radii; volume: the specimen's volume (m^3).
VoigtEstimate voigt_modulus(std::span<const Vec3> position, std::span<const double> radius,
                            std::span<const Index> bond_i, std::span<const Index> bond_j,
                            const BeamBondParameters& bond, double volume, const Vec3& axis);

struct CurvatureModulus {
  double youngs_modulus = 0;  // Pa
  double curvature = 0;       // 1/m, 2 c2
  double moment = 0;          // N m, F a / 2
  double force = 0;           // N, at the deformed frame
  std::size_t particles = 0;  // used in the fit
  double r_squared = 0;
  bool valid = false;
};

// reference/deformed: positions of the same particles (same order). Uses particles with
// |s| <= zone_fraction * pin_distance / 2. `down` is the loading direction.
CurvatureModulus curvature_modulus(std::span<const Vec3> reference, std::span<const Vec3> deformed,
                                   const Vec3& centre, const Vec3& axis, const Vec3& down,
                                   const BendingGeometry& geometry, double force, double zone_fraction = 0.8);

}  // namespace shard::bending
