#include "foreign_spring_bond.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "spring_effects.hpp"
#include "spring_kinematics.hpp"

namespace shard::foreign {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

ParamSpec number(const char* name, const char* unit, const char* doc, double value, double min, bool exclusive,
                 std::optional<double> neutral = std::nullopt) {
  return ParamSpec{.name = name,
                   .type = ParamType::Number,
                   .unit = unit,
                   .doc = doc,
                   .default_value = value,
                   .min = min,
                   .max = kInf,
                   .min_exclusive = exclusive,
                   .neutral = neutral};
}

struct Ends {
  Index first, second;
  bool swapped;  // the batch lists the bond (second, first)
};

// The lower stable id first, so a bond gives the same bits whichever way the kernel lists it.
Ends ends_of(const ParticleView& p, Index i, Index j) {
  return p.id[j] < p.id[i] ? Ends{j, i, true} : Ends{i, j, false};
}

SpringReference load(const double* s) {
  SpringReference r;
  r.rest_length = s[kRestLength];
  r.direction_first = Vec3(s[kDirectionFirst], s[kDirectionFirst + 1], s[kDirectionFirst + 2]);
  r.direction_second = Vec3(s[kDirectionSecond], s[kDirectionSecond + 1], s[kDirectionSecond + 2]);
  r.relative = Quat(s[kRelative + 3], s[kRelative], s[kRelative + 1], s[kRelative + 2]);
  return r;
}

void write_broken(BondBatch& b, std::size_t k, BondFailureMode mode) {
  b.force[k] = b.torque_i[k] = b.torque_j[k] = Vec3::Zero();
  b.energy[k] = 0;
  b.broken[k] = 1;
  // The law has forces, not stresses: only the failure mode is reported.
  b.stress[k] = BondStress{};
  b.stress[k].dominant = mode;
}

}  // namespace

std::vector<ParamSpec> spring_bond_params() {
  const SpringBondParams d;
  std::vector<ParamSpec> ps;
  ps.push_back(number("normal_stiffness", "N/m", "normal spring k_n", d.normal_stiffness, 0, true));
  ps.push_back(number("shear_stiffness", "N/m", "shear spring k_s", d.shear_stiffness, 0, true));
  ps.push_back(number("bending_stiffness", "N m/rad", "bending spring k_b", d.bending_stiffness, 0, true));
  ps.push_back(number("twisting_stiffness", "N m/rad", "twisting spring k_t", d.twisting_stiffness, 0, true));
  ps.push_back(number("normal_strength", "N", "tensile force at failure F_n,c", d.normal_strength, 0, true));
  ps.push_back(number("shear_strength", "N", "shear force at failure F_s,c", d.shear_strength, 0, true));
  ps.push_back(number("bending_strength", "N m", "bending moment at failure T_b,c", d.bending_strength, 0, true));
  ps.push_back(number("twisting_strength", "N m", "twisting moment at failure T_t,c", d.twisting_strength, 0, true));
  ps.push_back(number("damping_ratio", "1", "viscous damping ratio of each spring", d.damping_ratio, 0, false, 0.0));
  ps.push_back(ParamSpec{.name = "breakage",
                         .type = ParamType::Boolean,
                         .unit = "",
                         .doc = "bonds fail by the force criterion",
                         .default_value = true,
                         .min = -kInf,
                         .max = kInf,
                         .min_exclusive = false,
                         .neutral = 0.0});
  ps.push_back(number("weibull_modulus", "1", "strength scatter: Weibull modulus of a median-1 factor, 0 = none",
                      d.weibull_modulus, 0, false, 0.0));
  ps.push_back(ParamSpec{.name = "strength_seed",
                         .type = ParamType::Integer,
                         .unit = "1",
                         .doc = "seed of the strength draws",
                         .default_value = 0.0,
                         .min = 0,
                         .max = kInf,
                         .min_exclusive = false,
                         .neutral = std::nullopt});
  ps.push_back(number("softening_ratio", "1", "load ratio past 1 over which a bond softens to zero, 0 = brittle",
                      d.softening_ratio, 0, false, 0.0));
  ps.push_back(number("compression_ratio", "1", "normal stiffness in compression / k_n", d.compression_ratio, 0, true,
                      1.0));
  ps.push_back(number("fatigue_time", "s",
                      "subcritical damage: a bond fails once the integral of c^n / t_0 dt reaches 1 (c: its load "
                      "ratio), so it is weaker loaded slowly; 0 = none",
                      d.fatigue_time, 0, false, 0.0));
  ps.push_back(number("fatigue_exponent", "1", "n of the damage rate c^n / t_0", d.fatigue_exponent, 0, true));
  ps.push_back(number("cohesion_force", "N",
                      "a failed bond pulls its two particles together with this force until it is stretched past "
                      "cohesion_range; 0 = none",
                      d.cohesion_force, 0, false, 0.0));
  ps.push_back(number("cohesion_range", "m", "stretch past rest at which a failed bond's pull ends", d.cohesion_range,
                      0, true));
  return ps;
}

SpringBondParams SpringBondParams::from(const ParamSet& p) {
  SpringBondParams b;
  b.normal_stiffness = p.number("normal_stiffness");
  b.shear_stiffness = p.number("shear_stiffness");
  b.bending_stiffness = p.number("bending_stiffness");
  b.twisting_stiffness = p.number("twisting_stiffness");
  b.normal_strength = p.number("normal_strength");
  b.shear_strength = p.number("shear_strength");
  b.bending_strength = p.number("bending_strength");
  b.twisting_strength = p.number("twisting_strength");
  b.damping_ratio = p.number("damping_ratio");
  b.breakage = p.flag("breakage");
  b.weibull_modulus = p.number("weibull_modulus");
  b.strength_seed = static_cast<std::uint64_t>(p.integer("strength_seed"));
  b.softening_ratio = p.number("softening_ratio");
  b.compression_ratio = p.number("compression_ratio");
  b.fatigue_time = p.number("fatigue_time");
  b.fatigue_exponent = p.number("fatigue_exponent");
  b.cohesion_force = p.number("cohesion_force");
  b.cohesion_range = p.number("cohesion_range");
  return b;
}

SpringBond::SpringBond(const SpringBondParams& params) : p_(params) {
  const double positive[] = {p_.normal_stiffness, p_.shear_stiffness, p_.bending_stiffness, p_.twisting_stiffness,
                             p_.normal_strength,  p_.shear_strength,  p_.bending_strength,  p_.twisting_strength,
                             p_.compression_ratio, p_.fatigue_exponent, p_.cohesion_range};
  for (double v : positive)
    if (!(v > 0)) throw std::invalid_argument("foreign_spring_bond: stiffnesses, strengths, compression_ratio, fatigue_exponent and "
                                  "cohesion_range must be > 0");
  const double non_negative[] = {p_.damping_ratio, p_.weibull_modulus, p_.softening_ratio, p_.fatigue_time,
                                 p_.cohesion_force};
  for (double v : non_negative)
    if (!(v >= 0))
      throw std::invalid_argument("foreign_spring_bond: damping_ratio, weibull_modulus, softening_ratio, fatigue_time "
                                  "and cohesion_force must be >= 0");
}

void SpringBond::initialize(BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Ends e = ends_of(p, batch.i[k], batch.j[k]);
    const SpringReference r = spring_reference(p.position[e.first], p.position[e.second], p.orientation[e.first],
                                               p.orientation[e.second]);
    if (!(r.rest_length > 0)) throw std::invalid_argument("foreign_spring_bond: a bond joins two coincident particles");
    double* s = batch.state + k * kStateSize;
    s[kRestLength] = r.rest_length;
    for (int c = 0; c < 3; ++c) {
      s[kDirectionFirst + c] = r.direction_first[c];
      s[kDirectionSecond + c] = r.direction_second[c];
    }
    s[kRelative] = r.relative.x(), s[kRelative + 1] = r.relative.y(), s[kRelative + 2] = r.relative.z();
    s[kRelative + 3] = r.relative.w();
    s[kStrengthFactor] = strength_factor(p_.weibull_modulus, static_cast<std::uint64_t>(p.id[e.first]),
                                         static_cast<std::uint64_t>(p.id[e.second]), p_.strength_seed);
    s[kPeakRatio] = 0;
    s[kDamage] = 0;
    s[kCohesive] = 0;
  }
}

// 0.17 sqrt(m / K) as for Shard's bonds (a particle with ~10 bonds), for the translational
// springs against the lightest particle and for the rotational ones (bending, twisting, and the
// shear spring acting at half the rest length) against the smallest moment of inertia.
TimeStepLimit SpringBond::time_step_limit(const BondBatch& batch) const {
  const ParticleView& p = batch.particles;
  double lightest = kInf, smallest_inertia = kInf, longest = 0;
  for (std::size_t k = 0; k < batch.count; ++k) {
    const Index i = batch.i[k], j = batch.j[k];
    lightest = std::min({lightest, p.mass[i], p.mass[j]});
    smallest_inertia = std::min({smallest_inertia, p.inertia[i], p.inertia[j]});
    longest = std::max(longest, batch.state[k * kStateSize + kRestLength]);
  }
  TimeStepLimit limit;
  limit.name = "foreign_spring_bond 0.17 sqrt(m / k)";
  if (batch.count == 0) {
    limit.critical = limit.recommended = kInf;
    return limit;
  }
  const double k_translation = std::max({p_.normal_stiffness, p_.normal_stiffness * p_.compression_ratio,
                                         p_.shear_stiffness});
  const double k_rotation = std::max(p_.bending_stiffness, p_.twisting_stiffness) +
                            p_.shear_stiffness * 0.25 * longest * longest;
  // Damping ratio zeta shortens the explicit step by sqrt(1 + zeta^2) - zeta.
  const double damped = std::sqrt(1 + p_.damping_ratio * p_.damping_ratio) - p_.damping_ratio;
  limit.critical = damped * 0.17 * std::min(std::sqrt(lightest / k_translation), std::sqrt(smallest_inertia / k_rotation));
  limit.recommended = limit.critical;
  return limit;
}

void SpringBond::compute(BondBatch& batch) const {
  for (std::size_t k = 0; k < batch.count; ++k) compute_bond(batch, k);
}

void SpringBond::compute_bond(BondBatch& b, std::size_t k) const {
  const ParticleView& p = b.particles;
  const Ends e = ends_of(p, b.i[k], b.j[k]);
  const Index a = e.first, c = e.second;
  double* s = b.state + k * kStateSize;
  const SpringMotion m =
      spring_motion(load(s), p.position[a], p.position[c], p.orientation[a], p.orientation[c]);
  const Vec3 i_to_j = e.swapped ? Vec3(-m.normal) : m.normal;
  if (s[kCohesive] != 0) return compute_cohesive(b, k, m.stretch, i_to_j);

  // Elastic loads, all as acting on the first particle: it is pulled towards the second in
  // tension and dragged along the second's shear offset.
  const double k_n = m.stretch < 0 ? p_.normal_stiffness * p_.compression_ratio : p_.normal_stiffness;
  const double normal = k_n * m.stretch;
  const Vec3 shear = p_.shear_stiffness * m.shear;
  const Vec3 bending = p_.bending_stiffness * m.bending;
  const Vec3 twisting = p_.twisting_stiffness * m.twisting;

  double scale = 1;
  // A bond of an unbreakable zone takes the law without its breakage check (plugin ABI 5).
  if (p_.breakage && !bond_unbreakable(b.particles, b.i[k], b.j[k])) {
    const double w = s[kStrengthFactor];
    const double terms[4] = {std::max(normal, 0.0) / (w * p_.normal_strength), shear.norm() / (w * p_.shear_strength),
                             bending.norm() / (w * p_.bending_strength), twisting.norm() / (w * p_.twisting_strength)};
    const double criterion = terms[0] * terms[0] + terms[1] * terms[1] + terms[2] * terms[2] + terms[3] * terms[3];
    const auto largest = std::max_element(terms, terms + 4) - terms;
    const BondFailureMode mode[4] = {BondFailureMode::Tension, BondFailureMode::Shear, BondFailureMode::Bending,
                                     BondFailureMode::Torsion};
    if (p_.fatigue_time > 0)
      s[kDamage] += b.dt * fatigue_rate(std::sqrt(criterion), p_.fatigue_exponent, p_.fatigue_time);
    bool failed = s[kDamage] >= 1;
    if (p_.softening_ratio == 0) {
      failed = failed || criterion >= 1;
    } else {
      s[kPeakRatio] = std::max(s[kPeakRatio], std::sqrt(criterion));
      scale = softening_factor(s[kPeakRatio], p_.softening_ratio);
      failed = failed || scale <= 0;
    }
    if (failed) return fail(b, k, mode[largest], m.stretch, i_to_j);
  }

  // Damping on the relative velocity of the second particle seen from the pair's mean spin: zero
  // for a rigid motion.
  const Vec3 d = m.length * m.normal;
  const Vec3 v_rel = p.velocity[c] - p.velocity[a] - 0.5 * (p.omega[a] + p.omega[c]).cross(d);
  const double v_n = v_rel.dot(m.normal);
  const Vec3 v_s = v_rel - v_n * m.normal;
  const double reduced_mass = p.mass[a] * p.mass[c] / (p.mass[a] + p.mass[c]);
  const double reduced_inertia = p.inertia[a] * p.inertia[c] / (p.inertia[a] + p.inertia[c]);
  const double z2 = 2 * p_.damping_ratio;
  const double c_n = z2 * std::sqrt(k_n * reduced_mass), c_s = z2 * std::sqrt(p_.shear_stiffness * reduced_mass);
  const double c_r = z2 * std::sqrt(std::max(p_.bending_stiffness, p_.twisting_stiffness) * reduced_inertia);

  const Vec3 shear_on_first = scale * shear + c_s * v_s;
  const Vec3 force_on_first = (scale * normal + c_n * v_n) * m.normal + shear_on_first;
  // The shear pair of forces, a distance `length` apart, turns both particles alike.
  const Vec3 shear_torque = 0.5 * m.length * m.normal.cross(shear_on_first);
  const Vec3 spring_torque = scale * (bending + twisting) + c_r * (p.omega[c] - p.omega[a]);
  const Vec3 torque_first = shear_torque + spring_torque;
  const Vec3 torque_second = shear_torque - spring_torque;
  b.energy[k] = 0.5 * scale *
                (normal * m.stretch + shear.dot(m.shear) + bending.dot(m.bending) + twisting.dot(m.twisting));
  b.force[k] = e.swapped ? Vec3(-force_on_first) : force_on_first;
  b.torque_i[k] = e.swapped ? torque_second : torque_first;
  b.torque_j[k] = e.swapped ? torque_first : torque_second;
}

// Past its strength a bond breaks, or with a cohesion force it holds on as a pull alone.
void SpringBond::fail(BondBatch& b, std::size_t k, BondFailureMode mode, double stretch, const Vec3& i_to_j) const {
  if (p_.cohesion_force == 0) return write_broken(b, k, mode);
  b.state[k * kStateSize + kCohesive] = 1;
  compute_cohesive(b, k, stretch, i_to_j);
}

// A failed bond's cohesion: a constant pull along the bond (a bridge of binder or moisture left
// between the grains) up to cohesion_range past rest, then nothing; no shear, bending or
// twisting, no stored energy. Compression is the contact law's.
void SpringBond::compute_cohesive(BondBatch& b, std::size_t k, double stretch, const Vec3& i_to_j) const {
  if (stretch > p_.cohesion_range) return write_broken(b, k, BondFailureMode::Tension);
  b.force[k] = p_.cohesion_force * i_to_j;
  b.torque_i[k] = b.torque_j[k] = Vec3::Zero();
  b.energy[k] = 0;
}

}  // namespace shard::foreign
