// The sensor model of `shard synth`: each effect does what its equation says.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "shard/measure/features.hpp"
#include "shard/measure/statistics.hpp"
#include "shard/measure/synthetic.hpp"

using namespace shard::measure;

namespace {
Curve linear_truth(double k) {
  Curve c;
  for (int i = 0; i <= 1000; ++i) {
    c.time.push_back(i);
    c.displacement.push_back(1e-6 * i);
    c.force.push_back(k * 1e-6 * i);
  }
  return c;
}
}  // namespace

TEST_CASE("machine compliance: a series spring, 1/k_rec = 1/k + C") {
  const double k = 2e5, C = 2e-6;
  std::mt19937_64 rng(1);
  SensorModel s;
  s.machine_compliance = C;
  const Curve rec = record(linear_truth(k), s, rng);
  CHECK(*curve_features(rec)[Feature::Stiffness] == doctest::Approx(1 / (1 / k + C)).epsilon(1e-9));
}

TEST_CASE("noise, offset and quantisation have the requested sizes") {
  std::mt19937_64 rng(2);
  SensorModel s;
  s.force_noise = 0.3;
  s.displacement_step = 5e-6;
  const Curve truth = linear_truth(1e5);
  const Curve rec = record(truth, s, rng);
  std::vector<double> err;
  for (std::size_t k = 0; k < rec.size(); ++k) {
    err.push_back(rec.force[k] - truth.force[k]);
    const double steps = rec.displacement[k] / s.displacement_step;
    CHECK(std::abs(steps - std::round(steps)) < 1e-9);
    CHECK(std::abs(rec.displacement[k] - truth.displacement[k]) <= 0.5 * s.displacement_step + 1e-12);
  }
  // 1001 readings: the sample sd is within 3 x 0.3 / sqrt(2 x 1000) of 0.3.
  CHECK(sample_sd(err) == doctest::Approx(0.3).epsilon(0.07).scale(0));
  CHECK(std::abs(mean(err)) < 3 * 0.3 / std::sqrt(1000.0));
  CHECK(rec.u_force[0] == doctest::Approx(0.3));
  CHECK(rec.u_displacement[0] == doctest::Approx(5e-6 / std::sqrt(12.0)).scale(0));

  // Specimen scatter: force scale sd over many specimens.
  SensorModel scatter;
  scatter.specimen_scatter = 0.05;
  std::vector<double> scales;
  for (int i = 0; i < 400; ++i) scales.push_back(record(truth, scatter, rng).force.back() / truth.force.back());
  CHECK(sample_sd(scales) == doctest::Approx(0.05).epsilon(0.15).scale(0));  // sd of an sd estimate: 1/sqrt(2 x 400) = 3.5 %
}

TEST_CASE("seating closure: hyperbolic toe in series, half the gap at F_h, the full gap at large force") {
  const double k = 2e5, g = 4e-5, fh = 50;  // the truth reaches 200 N
  std::mt19937_64 rng(3);
  SensorModel s;
  s.seating_gap = g;
  s.seating_half_force = fh;
  const Curve truth = linear_truth(k);
  const Curve rec = record(truth, s, rng);
  for (std::size_t i = 0; i < rec.size(); ++i) {
    const double f = truth.force[i];
    CHECK(rec.displacement[i] - truth.displacement[i] == doctest::Approx(g * f / (f + fh)).epsilon(1e-12));
  }
  // Row 250 carries F = 50 N = F_h: half of the gap has closed; row 1000 (200 N = 4 F_h): 80 %.
  REQUIRE(truth.force[250] == doctest::Approx(fh));
  CHECK((rec.displacement[250] - truth.displacement[250]) / g == doctest::Approx(0.5).epsilon(1e-9));
  const std::size_t last = rec.size() - 1;
  CHECK((rec.displacement[last] - truth.displacement[last]) / g == doctest::Approx(0.8).epsilon(1e-9));
  SensorModel no_force;
  no_force.seating_gap = g;
  CHECK_THROWS(record(truth, no_force, rng));
}

TEST_CASE("a synthetic set: each rate's specimens recorded, zeroed at the preload and read with the known offset") {
  Specimen sim;
  sim.id = "seed1";
  sim.curve = linear_truth(1e5);  // 0.1 N per micrometre, to 100 N
  sim.crack_position = 0.004;
  sim.fragment_sizes = {0.05, 0.08};
  Specimen geometry;
  geometry.length = 0.18, geometry.width = 0.03, geometry.height = 0.035, geometry.span = 0.16, geometry.pin_distance = 0.08;
  SyntheticLab lab;
  lab.name = "lab";
  lab.sensor.force_noise = 0.03;
  lab.sensor.force_offset = 0.04;
  lab.test.seating_preload = 0.5;
  lab.test.zero_offset = 0.2;
  const MeasurementSet set = synthetic_set({{sim}, {sim}}, {0.02, 0.1}, geometry, lab);
  REQUIRE(set.specimens.size() == 2);
  CHECK(set.specimens[0].id == "seed1_rate0.02");
  CHECK(set.specimens[1].id == "seed1_rate0.1");
  CHECK(set.specimens[1].loading_rate == 0.1);
  CHECK(set.specimens[0].span == 0.16);
  CHECK(set.specimens[0].crack_position == 0.004);
  CHECK(set.specimens[0].fragment_sizes.size() == 2);
  CHECK(set.metadata.load_cell_uncertainty == doctest::Approx(0.05).scale(0));  // hypot(0.03, 0.04)
  // Zeroed where the (noisy) force first reaches 0.5 N: d = 0 there, the force read 0.5 N plus
  // the known offset, within the noise's few sigma.
  const Curve& c = set.specimens[0].curve;
  CHECK(c.displacement.front() == 0);
  CHECK(c.force.front() == doctest::Approx(0.5 + 0.2).epsilon(0.3).scale(0));
  // One noise stream over the set: the second rate's record is another draw of the same truth.
  CHECK(set.specimens[1].curve.force != c.force);
}
