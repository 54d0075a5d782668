#include "linear_spring_model.hpp"

#include <numbers>
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
      law_{k_n_, k_t_, 2.0 * zeta_, friction_},
      on_(effects.switches()),
      sizes_(effects.sizes(parameters.friction)),
      kernel_(linear::linear_kernel(contact::best_lane_set(), on_)) {}

LinearSpring LinearSpring::from(const ParamSet& params) {
  return LinearSpring(LinearSpringParameters::from(params),
                      contact::ContactEffects::from(params, "linear_spring", /*with_cohesion=*/false));
}

std::size_t LinearSpring::history_size() const { return contact::kTangentialHistorySize; }

// The shortest contact in a scene is between the two lightest particles (m* = m/2), and the
// stiffer of the normal and rolling-tangential oscillators sets its pace. The step is t_c / 20
// (docs/physics.md, Time step): stable and accurate for the spring, but the kernel's velocity Verlet feeds
// the dashpot the half-step velocity, so the realised restitution comes out high by about
// 5 % (e = 0.3), 3 % (e = 0.5), 1 % (e = 0.9); it falls in proportion to dt (tests/contact).
TimeStepLimit LinearSpring::time_step_limit(double min_radius, double density) const {
  const double lightest = density * 4.0 / 3.0 * std::numbers::pi * min_radius * min_radius * min_radius;
  const double t_contact = linear::contact_duration(linear::stiffest_oscillator(k_n_, k_t_), 0.5 * lightest);
  return {"linear_spring contact duration", t_contact, t_contact / 20.0};
}

void LinearSpring::compute(ContactBatch& batch) const { kernel_(contact::arrays_of(batch), law_, sizes_); }

void LinearSpring::compute_with(contact::LaneSet set, ContactBatch& batch) const {
  if (!contact::lane_set_available(set))
    throw std::invalid_argument(std::string("linear_spring: this machine cannot run the ") +
                                std::string(contact::lane_set_name(set)) + " lanes");
  linear::linear_kernel(set, on_)(contact::arrays_of(batch), law_, sizes_);
}

}  // namespace shard
