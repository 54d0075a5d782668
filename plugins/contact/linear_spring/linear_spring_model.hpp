#pragma once
// Linear spring-dashpot with Coulomb friction: the cheap baseline contact model (README.md).
#include <cstddef>

#include "shard/contact_model.hpp"
#include "shard/params.hpp"

namespace shard {

struct LinearSpringParameters {
  double normal_stiffness = 1e3;              // k_n, N/m
  double tangential_stiffness_ratio = 2.0 / 7.0;  // k_t / k_n, 1
  double friction = 0.67;                     // mu, 1
  double restitution = 0.5;                   // e, 1

  static LinearSpringParameters from(const ParamSet& params);
};

class LinearSpring final : public ContactModel {
 public:
  explicit LinearSpring(const LinearSpringParameters& parameters);

  std::size_t history_size() const override;
  TimeStepLimit time_step_limit(double min_radius, double density) const override;
  void compute(ContactBatch& batch) const override;

  double normal_stiffness() const { return k_n_; }
  double tangential_stiffness() const { return k_t_; }
  // Damping ratio zeta of both dashpots, solved from the restitution.
  double damping_ratio() const { return zeta_; }

 private:
  double k_n_;
  double k_t_;
  double friction_;
  double zeta_;
};

}  // namespace shard
