// Walls that turn about an axis: the contact geometry of a turned mesh, and particles carried by
// the surface velocity v + omega x r of a turntable and of a drum.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "kernel_fixtures.hpp"
#include "wall_spin_fixtures.hpp"

using namespace shard;

namespace {

// Three touching spheres of radius r in a triangle in the plane z = centre.z, bonded: a body
// that cannot roll on a surface without lifting a sphere, so on a moving surface it sticks or
// slides like a block. (A free sphere rolls instead: on a turntable it settles at 2/7 of the
// surface speed, as on a belt, test_wall_belt.cpp.)
SimulationSetup tripod(const Vec3& centre, double r, const BondModel& bond) {
  SimulationSetup setup;
  const double h = std::sqrt(3.0) * r;  // the triangle's height
  setup.particles.add(centre + Vec3(-r, -h / 3, 0), r, 2500.0);
  setup.particles.add(centre + Vec3(r, -h / 3, 0), r, 2500.0);
  setup.particles.add(centre + Vec3(0, 2 * h / 3, 0), r, 2500.0);
  setup.bonds = {{0, 1}, {1, 2}, {0, 2}};
  setup.bond = &bond;
  return setup;
}

std::unique_ptr<BondModel> damped_beam_bond() {
  auto& host = test::plugins();
  // Some bond damping (damping ratio ~0.02 of the pair's axial mode) so the body's own ringing
  // after it lands does not blur its velocity.
  return host.make_bond("beam_bond", host.params(PluginKind::Bond, "beam_bond", {{"damping", 0.5}}));
}

Vec3 mean_velocity(const Particles& p) {
  Vec3 v = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) v += p.velocity[k];
  return v / static_cast<double>(p.size());
}

Vec3 mean_position(const Particles& p) {
  Vec3 x = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) x += p.position[k];
  return x / static_cast<double>(p.size());
}

}  // namespace

TEST_CASE("a spinning mesh touches like the mesh turned by hand, and a full turn gives the same contacts") {
  const Vec3 centre(0.01, 0.0, 0.02), axis = Vec3(0.3, 1.0, 0.2).normalized();
  Wall spinning = test::drum_mesh(0.1, 0.06, 12);
  test::spin(spinning, centre, axis, 2 * std::numbers::pi);  // one turn per second
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.12, 0.12);
  std::vector<Vec3> points(200);
  for (auto& x : points) x = Vec3(u(rng), u(rng), u(rng));
  auto contacts = [&](const Wall& w, std::vector<Vec3>& normal, std::vector<double>& distance) {
    normal.assign(points.size(), Vec3::Zero());
    distance.assign(points.size(), -1.0);
    for (std::size_t k = 0; k < points.size(); ++k)
      if (!wall_contact(w, points[k], 0.05, normal[k], distance[k])) distance[k] = -1.0;
  };
  std::vector<Vec3> n0, n1;
  std::vector<double> d0, d1;

  // At 0.37 turns: the same mesh with its vertices turned about the axis, standing still. The
  // distances are differences of coordinates of size 0.1 m, so they agree to ~1e-17 m; 1e-12
  // leaves room for the two orders of operations.
  place_wall(spinning, 0.37);
  Wall turned = test::drum_mesh(0.1, 0.06, 12);
  const Mat3 rotation = Eigen::AngleAxisd(0.37 * 2 * std::numbers::pi, axis).toRotationMatrix();
  for (auto& t : turned.triangles)
    for (auto& v : t) v = centre + rotation * (v - centre);
  contacts(spinning, n0, d0);
  contacts(turned, n1, d1);
  int touching = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    CHECK(std::abs(d0[k] - d1[k]) < 1e-12);
    CHECK((n0[k] - n1[k]).norm() < 1e-9);  // a normal is a difference over a distance >= ~1e-3 m
    touching += d0[k] >= 0;
  }
  CHECK(touching > 20);  // the comparison covers many contacts, not only misses

  // A full turn: the angle is 2 pi, and the contacts are those at the start.
  place_wall(spinning, 1.0);
  CHECK(spinning.angle == doctest::Approx(2 * std::numbers::pi).epsilon(1e-15));
  contacts(spinning, n1, d1);
  place_wall(spinning, 0.0);
  contacts(spinning, n0, d0);
  for (std::size_t k = 0; k < points.size(); ++k) {
    CHECK(std::abs(d0[k] - d1[k]) < 1e-12);
    CHECK((n0[k] - n1[k]).norm() < 1e-9);
  }
}

TEST_CASE("a body on a turntable is carried round at v = omega x r") {
  // A plate in z = 0 turning about z at 3 rad/s after a 0.2 s 1-cos ramp; the body sits at 4 cm.
  // It sticks: the friction it needs, m (omega^2 r) = 0.36 m N/kg at the end and at most
  // m r omega pi / (2 T) = 0.94 m N/kg during the ramp, is below mu g = 4.9 m N/kg.
  auto model = test::linear_spring(1e4, 0.5, 0.5);
  auto bond = damped_beam_bond();
  const double r = 0.005, omega = 3.0;
  SimulationSetup setup = tripod(Vec3(0.04, 0, r - 2.0e-6), r, *bond);
  Wall plate;
  plate.shape = WallShape::Plane;
  plate.axis = Vec3::UnitZ();
  test::spin(plate, Vec3::Zero(), Vec3::UnitZ(), omega);
  plate.motion.ramp = WallRamp::OneMinusCos;
  plate.motion.ramp_time = 0.2;
  setup.walls.push_back(plate);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.contact = model.get();
  setup.dt = 1e-5;
  Simulation sim(std::move(setup));
  sim.run(60000);  // 0.6 s: 0.4 s at full speed, 0.19 turns
  const Vec3 x = mean_position(sim.particles()), v = mean_velocity(sim.particles());
  const Vec3 carried = Vec3(0, 0, omega).cross(Vec3(x.x(), x.y(), 0));
  CAPTURE(v.transpose());
  CAPTURE(carried.transpose());
  // Sticking, the body's velocity differs from the plate's only by the rate of change of the
  // tangential springs' stretch, m omega^2 r / k_t ~ 1e-8 m, which turns with the body: ~1e-7 m/s,
  // far below the 1e-3 relative allowed here for the springs' ringing left from the ramp.
  CHECK((v - carried).norm() < 1e-3 * carried.norm());
  CHECK(std::hypot(x.x(), x.y()) == doctest::Approx(0.04).epsilon(1e-3).scale(0));  // it did not slide out
  CHECK(sim.walls()[0].angular_speed == omega);
}

TEST_CASE("a body in a drum turning fast enough to hold it stays carried round with the drum") {
  // A 24-sided drum of radius 0.1 m about the y axis at 20 rad/s: omega^2 R = 40 m/s^2, four times
  // g, so the body is pressed on the drum all round, and with mu = 0.5 the friction available
  // (>= mu (omega^2 R - g) = 15 m/s^2 at the top) exceeds what gravity asks (<= g). The body
  // starts moving with the drum; over a full turn it must stay put on it. (Spun up from rest, a
  // body slides back down while omega^2 R < g and tumbles: no analytic result to test against.)
  auto model = test::linear_spring(1e4, 0.5, 0.5);
  auto bond = damped_beam_bond();
  const double r = 0.005, omega = 20.0, radius = 0.1;
  const double inscribed = radius * std::cos(std::numbers::pi / 24);
  // The body lies on the flat face at the bottom (the mesh turned half a face so that a face, not
  // an edge, is there), pressed in by its centripetal load m omega^2 R + m g over k = 6.2e-6 m.
  SimulationSetup setup = tripod(Vec3(0, 0, -(inscribed - r) - 6.2e-6), r, *bond);
  const Vec3 spin(0, omega, 0);
  for (std::size_t k = 0; k < 3; ++k) {
    setup.particles.velocity[k] = spin.cross(setup.particles.position[k]);
    setup.particles.omega[k] = spin;
  }
  Wall drum = test::drum_mesh(radius, 0.06, 24);
  const Mat3 half_face = Eigen::AngleAxisd(-std::numbers::pi / 24, Vec3::UnitY()).toRotationMatrix();
  for (auto& t : drum.triangles)
    for (auto& vertex : t) vertex = half_face * vertex;
  test::spin(drum, Vec3::Zero(), Vec3::UnitY(), omega);
  setup.walls.push_back(drum);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.contact = model.get();
  setup.dt = 1e-5;
  Simulation sim(std::move(setup));
  sim.run(35000);  // 0.35 s, 1.1 turns
  const Vec3 x = mean_position(sim.particles()), v = mean_velocity(sim.particles());
  const Vec3 carried = spin.cross(x);
  CAPTURE(v.transpose());
  CAPTURE(carried.transpose());
  // Turned with the drum: the body's angle in the x-z plane falls at omega from -pi/2 (the
  // right-hand rule about +y), by 7 rad in 0.35 s, within the 1e-3 rad that the springs' stretch
  // under the turning gravity allows.
  const double expected = -std::numbers::pi / 2 - omega * sim.time();
  const double turned = std::remainder(std::atan2(x.z(), x.x()) - expected, 2 * std::numbers::pi);
  CHECK(std::abs(turned) < 1e-3);
  // Gravity turns against the body once a turn (0.31 s, slow to the springs' ~1 ms period), so
  // the springs follow it quasi-statically: the slip rate ~ omega m g / k_t ~ 1e-4 m/s against
  // 1.9 m/s. 1e-3 relative bounds that and the ringing left from the start.
  CHECK((v - carried).norm() < 1e-3 * carried.norm());
  CHECK(std::hypot(x.x(), x.z()) == doctest::Approx(inscribed - r).epsilon(1e-3).scale(0));  // on the face it started on
  // The drum's torque sensor (about its axis) reads the body's weight times its lever arm: the
  // body's angular momentum about the axis is constant while it co-rotates, so the drum balances
  // gravity's torque on it. 5 % of W R covers the body's ringing.
  const double weight = 3 * sim.particles().mass[0] * 9.81;
  CHECK(std::abs(sim.walls()[0].torque.y() - weight * x.x()) < 0.05 * weight * radius);
}

TEST_CASE("a turning paddle sweeps into a sphere at rest: the neighbour list follows the turn") {
  // The paddle (6 cm long, about z) starts 1 rad behind a sphere at 5 cm and turns at 2 rad/s,
  // reaching it after 0.5 s, ~100 skins of travel at the sphere: without rebuilds for the wall's
  // turn the pair would never be listed and the sphere would stay put.
  auto model = test::linear_spring(1e4, 0.5, 0.5);
  SimulationSetup setup;
  setup.particles.add(Vec3(0.05 * std::cos(1.0), 0.05 * std::sin(1.0), 0), 0.005, 2500.0);
  Wall paddle = test::paddle_mesh(0.06, 0.02);
  test::spin(paddle, Vec3::Zero(), Vec3::UnitZ(), 2.0);
  setup.walls.push_back(paddle);
  setup.contact = model.get();
  setup.dt = 1e-5;
  Simulation sim(std::move(setup));
  sim.run(70000);  // 0.7 s
  const Vec3 v = sim.particles().velocity[0];
  // Struck by a surface moving at omega r = 0.1 m/s (the sphere's radius shifts the contact's
  // arm slightly), it leaves at least that fast ahead of the paddle: a light body hit by a
  // prescribed wall leaves at (1 + e) times the wall's normal speed, minus friction's share.
  CHECK(v.norm() > 0.1);
  CHECK(sim.walls()[0].impacts >= 1);
}

TEST_CASE("a plate turning in its own plane leaves its surface in place: a frictionless sphere on it stays put") {
  // Without friction the turning plate cannot drag the sphere, and the plate's surface does not
  // move, so the neighbour list is built once (at the start) in 0.5 s of turning at 10 rad/s;
  // a turn-blind bound would have rebuilt it every ~skin / (omega r) = 1e-3 / 0.4 s, ~200 times.
  auto model = test::linear_spring(1e4, 0.5, 0.0);
  SimulationSetup setup;
  setup.particles.add(Vec3(0.04, 0, 0.005 - 1.284e-6), 0.005, 2500.0);  // at its rest overlap m g / k
  Wall plate;
  plate.shape = WallShape::Plane;
  plate.axis = Vec3::UnitZ();
  test::spin(plate, Vec3::Zero(), Vec3::UnitZ(), 10.0);
  setup.walls.push_back(plate);
  setup.gravity = Vec3(0, 0, -9.81);
  setup.contact = model.get();
  setup.dt = 1e-5;
  Simulation sim(std::move(setup));
  sim.run(50000);
  CHECK_FALSE(sim.walls()[0].turn_moves_surface());
  CHECK(sim.neighbour_rebuilds() == 1);
  CHECK(std::abs(sim.particles().velocity[0].x()) + std::abs(sim.particles().velocity[0].y()) < 1e-12);
  CHECK(sim.contact_count() == 1);
}

TEST_CASE("a wall that translates and turns: its surface velocity is the time derivative of its surface points") {
  // A mesh moving on a linear ramp to (0.3, 0, -0.2) m/s while turning on a 1-cos ramp to 4 rad/s
  // about a tilted axis. A point fixed on the mesh sits at c0 + d(t) + R(theta(t)) (y0 - c0); its
  // velocity by central differences (step 1e-6 s: error ~ (1e-6)^2 x the third derivative ~ 1e-10
  // m/s here) must be what the contact uses, v + omega x (x - c).
  Wall w = test::drum_mesh(0.1, 0.06, 12);
  const Vec3 c0(0.02, -0.01, 0.03), axis = Vec3(0.2, 1.0, -0.4).normalized();
  test::spin(w, c0, axis, 4.0);
  w.motion.velocity = Vec3(0.3, 0, -0.2);
  w.motion.ramp = WallRamp::Linear;  // a ramp shapes both speeds
  w.motion.ramp_time = 0.1;
  const Vec3 y0 = w.triangles[5][1];  // a vertex of the mesh as read
  auto point_at = [&](double t) {
    place_wall(w, t);
    return Vec3(w.centre() + w.rotation * (y0 - c0));
  };
  for (double t : {0.02, 0.07, 0.25}) {
    CAPTURE(t);
    const double h = 1e-6;
    const Vec3 numeric = (point_at(t + h) - point_at(t - h)) / (2 * h);
    const Vec3 x = point_at(t);
    const Vec3 surface = w.surface_velocity_at(x, Vec3::UnitX());
    CHECK((surface - numeric).norm() < 1e-8);
    // The point is on the mesh: the contact finds it at distance zero from a point just off it.
    Vec3 normal;
    double distance = 0;
    REQUIRE(wall_contact(w, x + 1e-4 * (x - w.centre()).normalized(), 0.01, normal, distance));
    CHECK(distance <= 1e-4 + 1e-12);
  }
}
