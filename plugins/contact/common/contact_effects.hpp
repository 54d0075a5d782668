#pragma once
// The physical effects composed into a contact law (docs/reference/effects.md), each a policy with a name,
// its parameter and ONE neutral value, declared in its schema here and nowhere else:
//   cohesion          cohesion_stress sigma_c [Pa] (neutral 0): a pull sigma_c pi R* delta between
//                     touching particles (not at walls), the linear simplification of JKR
//   support_friction  support_friction_ratio r_w [1] (neutral 1): Coulomb friction at
//                     particle-wall contacts (supports, pins) r_w times the contact pair's mu
//   rolling_resistance rolling_friction mu_r [1] (neutral 0, per pair of materials): a couple
//                     against the relative rolling, an elastic-plastic spring-dashpot capped at
//                     mu_r R* F_n (contact_lanes.hpp); a sphere rolling on a plane decelerates
//                     at 5/7 mu_r g and comes to rest
// A policy joins the law when `effects` names it or its parameter is away from its neutral value;
// each is exact at its neutral value (at r_w = 1 the wall's mu is the particles' to the bit; a
// pull of 0 changes no bit), so naming it without moving its parameter reproduces the plain law.
// The policies run inside the law's lanes (contact_lanes.hpp), switched on at compile time.
//
// Cohesion: the net normal force is attractive below delta_eq = (3 pi sigma_c sqrt(R*) / (4 E*))^2
// and the quasi-static pull-off force is F_po = (pi sigma_c)^3 R*^2 / (12 E*^2) (Hertz law).
#include <numbers>
#include <string>
#include <vector>

#include "contact_lanes.hpp"
#include "shard/params.hpp"

namespace shard::contact {

struct ContactEffectPolicy {
  std::string name;
  std::string doc;
  ParamSpec param;  // with its neutral value
};

// The policies a law offers, in the order an error lists them: hertz_mindlin both, linear_spring
// support_friction only (cohesion's area pi R* delta is the Hertz contact's).
std::vector<ContactEffectPolicy> contact_effect_policies(bool with_cohesion);

// The `effects` key and the offered policies' parameters: what a law's schema adds.
std::vector<ParamSpec> contact_effect_params(bool with_cohesion);

struct ContactEffects {
  // Off (the schema's neutral values), for a model built in code; a scene's come from `from`.
  double cohesion_stress = 0;         // sigma_c, Pa
  double support_friction_ratio = 1;  // r_w, 1
  double rolling_friction = 0;        // mu_r, 1 ([contact]; [[material_pair]] rows give their own)
  std::vector<std::string> named;     // the policies `effects` lists

  // Reads the offered policies' parameters and `effects`; a name in `effects` that is no offered
  // policy throws, listing the valid ones (`law` names the plugin in the message).
  static ContactEffects from(const ParamSet& p, const char* law, bool with_cohesion);
  EffectSwitches switches() const;
  // Without rolling_friction: the law points it at its table of mu_r per pair when it computes.
  EffectSizes sizes() const { return {cohesion_stress, support_friction_ratio, nullptr}; }
  // Whether rolling resistance joins the law with these mu_r per pair of materials: named, or any
  // pair's mu_r away from its neutral 0.
  bool rolling_on(const std::vector<double>& mu_r_per_pair) const;
};

// What a law keeps of its effects: the given sizes, the switches, and mu_r per row of its law
// table (one row until set_materials gives a row per pair of materials).
struct ComposedEffects {
  ContactEffects given;
  EffectSwitches on;
  std::vector<double> rolling_friction;

  explicit ComposedEffects(const ContactEffects& effects);
  // mu_r of each pair of materials, row a * count + b as the law's table; rolling resistance is
  // switched on when named or when any pair's mu_r is away from 0.
  void set_pairs(const std::vector<ParamSet>& pairs);
  // The sizes the lanes read, rolling_friction pointing at this table (valid while it lives).
  EffectSizes sizes() const;
  // The contact history a law with these effects keeps, doubles per contact.
  std::size_t history_size() const { return on.rolling_resistance ? kRollingHistorySize : kTangentialHistorySize; }
};

inline double pull_off_force(double sigma_c, double R, double E_star) {
  const double p = std::numbers::pi * sigma_c;
  return p * p * p * R * R / (12 * E_star * E_star);
}

}  // namespace shard::contact
