#include "linear_spring_model.hpp"

#include <algorithm>
#include <numbers>
#include <utility>
#include <stdexcept>
#include <string>

#include "../common/contact_batch_arrays.hpp"
#include "linear_damping.hpp"
#include "linear_equations.hpp"
#include "linear_kernels.hpp"

namespace shard {

LinearSpringParameters LinearSpringParameters::from(const ParamSet& params) {
  return {params.number("normal_stiffness"), params.number("tangential_stiffness_ratio"),
          params.number("friction"), params.number("restitution")};
}

namespace {

const LinearSpringParameters& checked(const LinearSpringParameters& p) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("linear_spring: ") + what);
  };
  require(p.normal_stiffness > 0.0, "normal_stiffness must be > 0 N/m");
  require(p.tangential_stiffness_ratio > 0.0, "tangential_stiffness_ratio must be > 0");
  require(p.friction >= 0.0, "friction must be >= 0");
  require(p.restitution > 0.0 && p.restitution <= 1.0, "restitution must lie in (0, 1]");
  return p;
}

}  // namespace

LinearSpring::LinearSpring(const LinearSpringParameters& parameters, const contact::ContactEffects& effects)
    : k_n_(checked(parameters).normal_stiffness),
      k_t_(parameters.tangential_stiffness_ratio * parameters.normal_stiffness),
      friction_(parameters.friction),
      zeta_(linear::damping_ratio_for_restitution(parameters.restitution)),
      laws_{linear::LinearLaw{{k_n_, k_t_, 2.0 * zeta_, friction_}}},
      effects_(effects),
      kernel_(linear::linear_kernel(contact::best_lane_set(), effects_.on)) {}

LinearSpring LinearSpring::from(const ParamSet& params) {
  return LinearSpring(LinearSpringParameters::from(params),
                      contact::ContactEffects::from(params, "linear_spring", /*with_cohesion=*/false));
}

std::size_t LinearSpring::history_size() const { return effects_.history_size(); }

// The shortest contact in a scene is between the two lightest particles (m* = m/2), and the
// stiffer of the normal and rolling-tangential oscillators sets its pace. The step is t_c / 20
// (docs/explanation/physics.md, Time step): stable and accurate for the spring, but the kernel's velocity Verlet feeds
// the dashpot the half-step velocity, so the realised restitution comes out high by about
// 5 % (e = 0.3), 3 % (e = 0.5), 1 % (e = 0.9); it falls in proportion to dt (tests/contact).
TimeStepLimit LinearSpring::time_step_limit(double min_radius, double density) const {
  const double lightest = density * 4.0 / 3.0 * std::numbers::pi * min_radius * min_radius * min_radius;
  // The first pair's springs (the only one, unless set_materials gave a table of one).
  const double* law = laws_[0].constant;
  const double t_contact = linear::contact_duration(
      linear::stiffest_oscillator(law[linear::LinearLaw::kNormalStiffness], law[linear::LinearLaw::kTangentialStiffness]),
      0.5 * lightest);
  return {"linear_spring contact duration", t_contact, t_contact / 20.0};
}

void LinearSpring::set_materials(const ContactMaterials& m) {
  const std::size_t n = m.count;
  if (n == 0 || m.pair.size() != n * n || m.names.size() != n)
    throw std::invalid_argument("linear_spring: a material table needs one entry per material and per pair");
  std::vector<linear::LinearLaw> laws(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      LinearSpringParameters p;
      try {
        p = checked(LinearSpringParameters::from(m.pair[a * n + b]));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string(e.what()) + " (materials '" + m.names[a] + "' and '" + m.names[b] + "')");
      }
      const double k_t = p.tangential_stiffness_ratio * p.normal_stiffness;
      laws[a * n + b] = linear::LinearLaw{
          {p.normal_stiffness, k_t, 2.0 * linear::damping_ratio_for_restitution(p.restitution), p.friction}};
    }
  count_ = n;
  names_ = m.names;
  laws_ = std::move(laws);
  effects_.set_pairs(m.pair);
  kernel_ = linear::linear_kernel(contact::best_lane_set(), effects_.on);
}

// Each pair on its lightest particles: m* of the two lightest (m/2 for one material), or the
// particle's own mass against a material no particle is made of (a wall's).
TimeStepLimit LinearSpring::time_step_limit(const std::vector<MaterialExtent>& per_material) const {
  const auto lightest = [&](std::size_t a) {
    const double r = per_material[a].min_radius;
    return per_material[a].density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  };
  TimeStepLimit out{"linear_spring contact duration", 0, 0};
  bool any = false;
  const std::size_t n = std::min(per_material.size(), count_);
  for (std::size_t a = 0; a < n; ++a) {
    if (!(per_material[a].min_radius > 0)) continue;
    for (std::size_t b = 0; b < n; ++b) {
      const bool particles = per_material[b].min_radius > 0;
      const double m_a = lightest(a), m_b = particles ? lightest(b) : 0.0;
      const double m_eff = !particles ? m_a : (a == b ? 0.5 * m_a : m_a * m_b / (m_a + m_b));
      const linear::LinearLaw& law = laws_[a * count_ + b];
      const double t = linear::contact_duration(
          linear::stiffest_oscillator(law.constant[linear::LinearLaw::kNormalStiffness],
                                      law.constant[linear::LinearLaw::kTangentialStiffness]),
          m_eff);
      if (any && !(t < out.critical)) continue;
      any = true;
      out = {"linear_spring contact duration (" + names_[a] + " on " + names_[b] + ")", t, t / 20.0};
    }
  }
  return out;
}

void LinearSpring::compute(ContactBatch& batch) const { kernel_(contact::arrays_of(batch), laws_.data(), effects_.sizes()); }

void LinearSpring::compute_with(contact::LaneSet set, ContactBatch& batch) const {
  linear::linear_kernel.required(set, effects_.on, "linear_spring")(contact::arrays_of(batch), laws_.data(), effects_.sizes());
}

}  // namespace shard
