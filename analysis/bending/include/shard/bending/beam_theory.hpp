#pragma once
// Elastic beam theory of the four-point bending test (seed sec. V.2-3; docs/explanation/four-point-bending.md).
//
// Two supports `span` apart, two loading pins `pin_distance` apart centred between them, the
// total force F shared equally by the pins. With the shear span a = (span - pin_distance) / 2:
//   eq. 14  w_s = F (span - d)^2 (span + 2 d) / (48 E I),  I = b h^3 / 12,
//           the deflection under a pin relative to the supports (Euler-Bernoulli);
//   eq. 15  sigma_b = 3 F (span - d) / (2 b h^2), the outer-fibre stress between the pins,
//           where the bending moment is constant: M = F a / 2.
// The seed's "48 E/I" is a typo for 48 E I. The seed takes span = L_S (180 mm).
namespace shard::bending {

struct BendingGeometry {
  double span = 0.180;          // m, distance between the support lines (L_S in eq. 14-15)
  double pin_distance = 0.080;  // m, distance between the loading pins (d_S)
  double width = 0.030;         // m, b_S (along the pins)
  double height = 0.035;        // m, h_S (along the load)

  double shear_span() const { return 0.5 * (span - pin_distance); }  // a, m
  double second_moment() const { return width * height * height * height / 12.0; }  // I, m^4
  // Throws std::invalid_argument unless 0 < pin_distance < span and b, h > 0.
  void check() const;
};

// w_s / F of eq. 14 times E: the pin deflection per unit force is compliance_factor / E.
double compliance_factor(const BendingGeometry& g);  // (L-d)^2 (L+2d) / (48 I), 1/m
// E = F / (w_s * 48 I) (L-d)^2 (L+2d): eq. 14 solved for E with a stiffness k = F / w_s (N/m).
double youngs_modulus_from_stiffness(const BendingGeometry& g, double stiffness);
// Eq. 14 forward: the stiffness F / w_s of a beam of modulus E (N/m).
double stiffness_from_youngs_modulus(const BendingGeometry& g, double youngs_modulus);
// Eq. 15: outer-fibre stress at total force F (Pa), and its inverse.
double flexural_stress(const BendingGeometry& g, double force);
double force_from_flexural_stress(const BendingGeometry& g, double stress);
// Timoshenko's shear deflection under a pin, F a / (2 k_s G A), added to eq. 14 for a beam of
// finite depth: returns the ratio shear / bending deflection = E h^2 / (k_s G (L-d)(L+2d)),
// with the rectangular section's k_s = 5/6. For L = 180, d = 80, h = 35 mm and E/G = 2.5 it
// is 0.11: eq. 14 applied to a measured stiffness underestimates E by that much.
double shear_to_bending_deflection(const BendingGeometry& g, double youngs_over_shear_modulus);

}  // namespace shard::bending
