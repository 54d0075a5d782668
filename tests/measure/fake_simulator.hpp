#pragma once
// A simulator of analytic four-point bending curves for the measurement science's decision paths:
// each model plan's overrides set the parameters of a closed-form curve, so a diagnosis runs in
// milliseconds and its verdicts can be asserted against a known truth. The curve rises as
// F = F_p x (1 + n (1 - x)), x = w / w_p, to its peak and falls linearly to zero over d w_p:
//   stiffness    k   = 1e-3 E (1 + 0.8 r) (1 + 0.5 (1 - exp(-g)))      [N/m]   E: bond.youngs_modulus
//   peak force   F_p = 2.5e-4 S (1 + 0.5 r) (1 + 0.15 (c - 1)) (1 + 0.2 g)  S: bond.critical_stress
//   nonlinearity n   = 0.08 + 0.1 s,  ductility d = 0.15 + 0.4 s         s: fake.softening
// r = mu - 0.3 above the reference's roller friction mu = 0.3, a quarter of that below (support.friction:
// no mirror image either way), c: fake.compression_ratio, and the library's
// machine compliance through recorded_as_tested. fake.softening_twin acts as fake.softening (a
// rival with the same signature); fake.toe (outside any library) adds slack before the rise;
// g: fake.stiffening, whose response bends with its size (the stiffness saturates while the
// strength keeps growing), so its contrast at one size is no multiple of its contrast at another.
// h: fake.onset, whose response changes direction with its size: stiffness and strength grow
// together up to h = 2 and stay there, and beyond h = 2.5 only the ductility grows (a second
// mechanism sets in, as a crack that moves to another site once the effect is strong enough):
//   k, F_p x (1 + 0.2 min(h, 2)),   d + 0.03 max(0, h - 2.5).
// r: fake.redraw, a change that redraws the fracture as a brittle DEM model's slightest change
// does: F_p x exp(0.1 r) on odd seeds and exp(-0.1 r) on even ones, so its mean over seeds 1-3 is
// a third of that up, which no seed agrees on.
// Each packing seed scatters k, F_p, n and d by ~1 %, as a random packing does.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "shard/measure/simulator.hpp"

namespace shard::measure::fake {

inline const std::map<std::string, double>& defaults() {
  static const std::map<std::string, double> d{{"bond.youngs_modulus", 1e7}, {"bond.critical_stress", 2e5},
                                               {"fake.softening", 0},         {"fake.softening_twin", 0},
                                               {"support.friction", 0.3},     {"fake.compression_ratio", 1},
                                               {"fake.toe", 0},               {"fake.stiffening", 0},
                                               {"fake.onset", 0},                {"fake.redraw", 0},
                                               {"generator.diameter_min", 0.005},
                                               {"generator.diameter_max", 0.0065}};
  return d;
}

// A standard normal draw from a hash of (seed, stream): the same for every model on one seed.
inline double normal_draw(std::uint64_t seed, std::uint64_t stream) {
  auto uniform = [](std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    x ^= x >> 31;
    return (static_cast<double>(x >> 11) + 0.5) * 0x1.0p-53;
  };
  const double u1 = uniform(seed * 1000003 + 2 * stream), u2 = uniform(seed * 1000003 + 2 * stream + 1);
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

struct Parameters {
  std::map<std::string, double> values = defaults();
  double at(const std::string& key) const { return values.at(key); }
};

inline Parameters parameters_of(const ModelPlan& model) {
  Parameters p;
  for (const auto& o : model.overrides) {
    if (!p.values.count(o.key)) throw std::invalid_argument("fake simulator: unknown parameter " + o.key);
    if (const auto* d = std::get_if<double>(&o.value)) p.values[o.key] = *d;
    else if (const auto* i = std::get_if<std::int64_t>(&o.value)) p.values[o.key] = static_cast<double>(*i);
  }
  return p;
}

// One curve: `scatter` is the relative sd of k and F_p over seeds (specimens or packings).
inline Curve curve_of(const Parameters& p, std::uint64_t seed, double scatter, double rate) {
  const double mu = p.at("support.friction"), s = p.at("fake.softening") + p.at("fake.softening_twin");
  // Roller friction restrains the beam more the more there is, and saturates towards none.
  const double restraint = mu >= 0.3 ? mu - 0.3 : 0.25 * (mu - 0.3);
  const double g = p.at("fake.stiffening");
  const double h = p.at("fake.onset");
  const double onset_gain = 1 + 0.2 * std::min(h, 2.0);
  const double redrawn = std::exp(0.1 * p.at("fake.redraw") * (seed % 2 == 1 ? 1.0 : -1.0));
  const double k = 1e-3 * p.at("bond.youngs_modulus") * (1 + 0.8 * restraint) * (1 + 0.5 * (1 - std::exp(-g))) *
                   onset_gain * std::exp(scatter * normal_draw(seed, 1));
  const double f_p = 2.5e-4 * p.at("bond.critical_stress") * (1 + 0.5 * restraint) *
                     (1 + 0.15 * (p.at("fake.compression_ratio") - 1)) * (1 + 0.2 * g) * onset_gain * redrawn *
                     std::exp(scatter * normal_draw(seed, 2));
  // The curve's form scatters too (a packing's weakest bonds are its own), so no component of a
  // contrast is free of noise and its covariance is not singular.
  const double n = (0.08 + 0.1 * s) * std::exp(0.25 * scatter * normal_draw(seed, 3));
  const double d = (0.15 + 0.4 * s + 0.03 * std::max(0.0, h - 2.5)) * std::exp(0.25 * scatter * normal_draw(seed, 4));
  const double toe = p.at("fake.toe");
  const double w_p = f_p * (1 + n) / k;
  Curve c;
  const double w_end = toe + w_p * (1.3 + d);
  for (int i = 0; i <= 400; ++i) {
    const double w = w_end * i / 400.0, x = (w - toe) / w_p;
    double f = 0;
    if (x > 0 && x <= 1) f = f_p * x * (1 + n * (1 - x));
    else if (x > 1) f = std::max(0.0, f_p * (1 - (x - 1) / d));
    c.displacement.push_back(w);
    c.force.push_back(f);
    c.time.push_back(w / rate);
    c.u_force.push_back(0.05);
    c.u_displacement.push_back(1e-6);
  }
  return c;
}

inline Specimen specimen_of(const Parameters& p, std::uint64_t seed, double scatter, double rate) {
  Specimen s;
  s.id = "seed" + std::to_string(seed);
  s.length = 0.18, s.width = 0.03, s.height = 0.035, s.span = 0.17, s.pin_distance = 0.08;
  s.loading_rate = rate;
  s.curve = curve_of(p, seed, scatter, rate);
  return s;
}

// A library entry for one of the fake's parameters (or kMachineCompliance).
inline CandidateEffect effect(const std::string& name, const std::string& parameter, double neutral, double plausible,
                              double min, double max) {
  CandidateEffect e;
  e.name = name, e.parameter = parameter, e.neutral = neutral, e.plausible = plausible, e.min = min, e.max = max;
  return e;
}

// A measured set: four specimens of the truth (parameters by key; the defaults elsewhere) at
// 0.02 m/s, each with its own `scatter` (2 %: a lab's batch), recorded through the load frame's
// `compliance`. Seeds from `first_seed` on, apart from the model's packing seeds 1, 2, 3.
inline MeasurementSet measured_set(const std::map<std::string, double>& truth, std::uint64_t first_seed,
                                   double compliance = 0, double scatter = 0.02) {
  Parameters p;
  for (const auto& [k, v] : truth) p.values.at(k) = v;
  MeasurementSet set;
  set.folder = "set" + std::to_string(first_seed);
  ModelPlan as_tested;
  as_tested.machine_compliance = compliance;
  for (std::uint64_t k = 0; k < 4; ++k)
    set.specimens.push_back(recorded_as_tested(specimen_of(p, first_seed + k, scatter, 0.02), as_tested, {}, "lab"));
  return set;
}

// A beam that is not bent up to a fracture (it slides off its rollers, or crushes at them): the
// force the pins meet first (a third of the peak) falls to zero over the travel.
inline void without_rise(Curve& c) {
  const double f0 = *std::max_element(c.force.begin(), c.force.end()) / 3, w_end = c.displacement.back();
  for (std::size_t k = 0; k < c.size(); ++k) c.force[k] = f0 * (1 - c.displacement[k] / w_end);
}

class FakeSimulator final : public Simulator {
 public:
  explicit FakeSimulator(int seeds = 3) : seeds_(seeds) {}

  // A run softened beyond this fails, as a DEM beam that breaks before the pins load it.
  double softening_limit = std::numeric_limits<double>::infinity();
  // Below this roller friction the model's beam slides off its rollers and never bends: its force
  // falls from the moment the pins touch (a curve with no rise to a peak).
  double sliding_friction = 0;
  // Below this bond modulus the model's beam crushes at its rollers: a curve with no rise.
  double crushing_modulus = 0;
  // Below this bond modulus the model's beam beds into its rollers and shows half its stiffness,
  // as a DEM beam whose grains crush at the fixture: a response that turns back on a fit.
  double bedding_modulus = 0;

  std::vector<std::vector<Specimen>> simulate(const std::vector<ModelPlan>& models, std::ostream&) override {
    std::vector<std::vector<Specimen>> out;
    for (const auto& m : models) {
      Parameters p = parameters_of(m);
      if (p.at("bond.youngs_modulus") < bedding_modulus) p.values["bond.youngs_modulus"] *= 0.5;
      if (p.at("fake.softening") > softening_limit)
        throw std::runtime_error("fake run: the curve never reaches the seating preload (softened beyond the limit)");
      std::vector<Specimen> replicates;
      for (int seed = 1; seed <= seeds_; ++seed) {
        Specimen run = specimen_of(p, static_cast<std::uint64_t>(seed), 0.01, m.loading_rate);
        if (p.at("support.friction") < sliding_friction || p.at("bond.youngs_modulus") < crushing_modulus)
          without_rise(run.curve);
        replicates.push_back(recorded_as_tested(std::move(run), m, test_, "fake run"));
      }
      out.push_back(std::move(replicates));
      ++runs_;
    }
    return out;
  }
  void check_inputs(const ModelPlan&, const std::vector<Specimen>&, const Metadata& metadata) override {
    test_ = metadata.test;
  }
  void check_model(const ModelPlan& model) override { parameters_of(model); }
  double parameter(const ModelPlan& model, const std::string& key) const override {
    return parameters_of(model).at(key);
  }
  ParameterRange parameter_range(const std::string& key) const override {
    if (key == "support.friction") return {0, 2};
    return {0, std::numeric_limits<double>::infinity()};
  }
  RunHealth health() const override { return {}; }
  int models_simulated() const { return runs_; }

 private:
  int seeds_;
  int runs_ = 0;
  TestConditions test_;
};

}  // namespace shard::measure::fake
