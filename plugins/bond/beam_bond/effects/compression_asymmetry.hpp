#pragma once
// Tension/compression asymmetry of the axial spring: E_b A_b / l0 while the bond is stretched,
// r E_b A_b / l0 while it is shortened (Gamma_x < 0). Shear, bending, torsion and the strength are
// unchanged (the axial stress counts in the von Mises check only in tension). Neutral r = 1.
#include "shard/lanes/lanes.hpp"

namespace shard::beam {

// The axial modulus for the axial strain gamma_x: E_b, or r E_b = `compression_modulus` in
// compression; for any lane type T (shard/lanes/lanes.hpp).
template <class T>
inline T axial_modulus(const T& gamma_x, const T& youngs, const T& compression_modulus) {
  using namespace lanes;
  return select(gamma_x < 0.0, compression_modulus, youngs);
}

}  // namespace shard::beam
