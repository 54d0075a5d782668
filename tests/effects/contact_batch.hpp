#pragma once
// The effect tests call contact models by hand exactly as the contact tests do (outputs zeroed,
// history kept between calls); their contacts default to a vertical normal.
#include "../contact/contact_arrays.hpp"

namespace shard::effects_test {

struct ContactScene : test::ContactArrays {
  ContactScene(std::size_t n, std::size_t history_stride) : ContactArrays(n, history_stride) {
    normal.assign(n, Vec3::UnitZ());
  }
  void compute(const ContactModel& model, double dt) {
    ContactBatch b = batch(dt);
    model.compute(b);
  }
};

}  // namespace shard::effects_test
