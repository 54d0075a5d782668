#include "shard/simulation.hpp"

#include <fmt/format.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "contact_candidates.hpp"
#include "contact_candidates_scalar.hpp"
#include "contact_geometry.hpp"
#include "contact_geometry_scalar.hpp"
#include "drift_lanes.hpp"
#include "huge_pages.hpp"
#include "neighbour_list.hpp"
#include "pair_exclusion.hpp"
#include "parallel.hpp"
#include "prefetch_rows.hpp"
#include "spatial_order.hpp"

namespace shard {
namespace {

// The contact pass looks at tiles of this many listed pairs and calls the contact model on the
// touching ones, a block of at most as many contacts. A block's geometry, history
// and forces (~200 bytes per contact) stay in L1 from the geometry pass through the model to the
// scatter; one array for all of a thread's contacts (6 MB in the bonded block) went out to memory
// and came back twice per step.
constexpr std::size_t kContactBlock = 128;

// One thread's block of touching pairs, structure of arrays (the ContactBatch layout).
struct ContactArrays {
  std::size_t count = 0;
  std::vector<Index> i, j;
  std::vector<std::size_t> pair;
  std::vector<std::int32_t> material_pair;  // per contact: the materials' row of the law table
  std::vector<std::uint8_t> touched;    // per contact: it touched at the last pass too (not a new impact)
  std::vector<Vec3> normal, velocity, omega_rel, force, couple;
  std::vector<Vec3> torque_a, torque_b;  // a particle pair's loads on its ends besides the force
  std::vector<double> overlap, r_eff, m_eff, energy, history;
  void reserve(std::size_t stride) {
    const std::size_t n = kContactBlock;
    if (i.size() == n + 8 && history.size() == n * stride) return;
    // A group of the candidate lanes stores 8 slots past its last candidate (contact_candidates.hpp).
    i.resize(n + 8);
    j.resize(n + 8);
    pair.resize(n + 8);
    material_pair.resize(n);
    touched.resize(n + 8);
    normal.resize(n);
    velocity.resize(n);
    omega_rel.resize(n);
    force.resize(n);
    couple.resize(n);
    torque_a.resize(n);
    torque_b.resize(n);
    overlap.resize(n);
    r_eff.resize(n);
    m_eff.resize(n);
    energy.resize(n);
    history.resize(n * stride);
  }
};

// One thread's share of a force pass. Thread 0 adds straight into the particle arrays, thread
// t > 0 into its own buffers, which are summed into the particles in thread order afterwards
// (and left zero again): no atomics, no locks, and a fixed order of every sum.
constexpr std::size_t kBondBlock = 256;  // bonds per batch call: a block's loads fit in L1

// A wall contact of this step, kept until the particles' whole forces are known (wall_touch_work).
struct WallTouch {
  Index particle;
  std::size_t wall;
  Vec3 force, couple, arm;  // on the particle; arm from its centre to the contact point
  Vec3 velocity, omega_rel;  // relative to the surface, at the half step before the forces
};

struct alignas(64) ThreadShare {
  std::vector<Vec3> force, torque;
  ContactArrays block;
  std::vector<Vec3> wall_force, wall_torque;
  std::vector<double> wall_stored;
  std::vector<std::int64_t> wall_impacts;
  // Grows to the most wall contacts a thread has had and keeps that capacity: no allocation once
  // the run has warmed up.
  std::vector<WallTouch> wall_touches;
  std::vector<WallContactStart> wall_begun;  // the same: capacity kept
  std::vector<Vec3> block_force, block_torque_i, block_torque_j;
  std::vector<double> block_energy;
  double bond_energy = 0;
  double contact_energy = 0;
  std::size_t contacts = 0;
  bool bond_broke = false;

  // Empties the share's wall loads and totals for a force pass (the force buffers are left zero by
  // the previous pass's sum).
  void start_pass() {
    std::fill(wall_force.begin(), wall_force.end(), Vec3::Zero());
    std::fill(wall_torque.begin(), wall_torque.end(), Vec3::Zero());
    std::fill(wall_stored.begin(), wall_stored.end(), 0.0);
    std::fill(wall_impacts.begin(), wall_impacts.end(), 0);
    wall_touches.clear();
    wall_begun.clear();
    contact_energy = 0;
    contacts = 0;
    bond_broke = false;
    bond_energy = 0;
  }
};

// The work of one wall contact's force and couple on particle a's motion relative to the surface
// over one step, J (negative when the particle loses energy). Velocity Verlet changes the kinetic
// energy over the step from v(n-1/2) to v(n+1/2) by exactly F(n) . v(n) dt, v(n) the mean of the
// two, v(n-1/2) + (dt/2) F(n) / m with the particle's whole force (contacts, bonds, gravity,
// damping), and likewise for the spin. Summed over an impact it is the kinetic energy the particle
// lost to the contact, to round-off.
double wall_touch_work(const Particles& p, const WallTouch& c, double dt) {
  const auto a = static_cast<std::size_t>(c.particle);
  const double h = p.flags[a] & (kFixed | kPrescribed) ? 0.0 : 0.5 * dt;  // held particles get no kick
  const Vec3 spin_kick = h * p.torque[a] / p.inertia[a];
  const Vec3 v = c.velocity + h * p.force[a] / p.mass[a] + spin_kick.cross(c.arm);
  return dt * (c.force.dot(v) + c.couple.dot(c.omega_rel + spin_kick));
}

double density_of(const Particles& p, std::size_t k) {
  const double r = p.radius[k];
  return p.mass[k] / (4.0 / 3.0 * std::numbers::pi * r * r * r);
}

// to -= damping |to| sign(v), per component, sign(v) 1, -1 or 0 (0 for NaN too). Without a branch:
// in a solid the sign of each velocity component is close to random from particle to particle, and
// the branches GCC makes of `v > 0 ? 1 : (v < 0 ? -1 : 0)` are mispredicted (a tenth of the damped
// seed beam's step). The same IEEE operations in the same order as the scalar expression.
[[gnu::always_inline]] inline void damp3(double* to, const double* v, double damping) {
#if defined(__SSE2__)
  const __m128d one = _mm_set1_pd(1.0), zero = _mm_setzero_pd(), d = _mm_set1_pd(damping);
  const __m128d magnitude = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffff));
  const auto damped = [&](__m128d f, __m128d u) {
    const __m128d sign = _mm_sub_pd(_mm_and_pd(_mm_cmpgt_pd(u, zero), one), _mm_and_pd(_mm_cmplt_pd(u, zero), one));
    return _mm_sub_pd(f, _mm_mul_pd(_mm_mul_pd(d, _mm_and_pd(f, magnitude)), sign));
  };
  _mm_storeu_pd(to, damped(_mm_loadu_pd(to), _mm_loadu_pd(v)));
  _mm_store_sd(to + 2, damped(_mm_load_sd(to + 2), _mm_load_sd(v + 2)));
#else
  for (int c = 0; c < 3; ++c)
    to[c] -= damping * std::abs(to[c]) * (static_cast<double>(v[c] > 0) - static_cast<double>(v[c] < 0));
#endif
}

// Gravity and Cundall's local non-viscous damping (opposes the motion with a fraction of the
// force) on particle k, once its pair and bond forces are complete.
[[gnu::always_inline]] inline void add_body_forces(Particles& p, std::size_t k, bool gravity, const Vec3& g, double damping) {
  if (gravity) p.force[k] += p.mass[k] * g;
  if (damping > 0) {
    damp3(p.force[k].data(), p.velocity[k].data(), damping);
    damp3(p.torque[k].data(), p.omega[k].data(), damping);
  }
}

// The second half-kick of velocity Verlet on particle k once its force is complete; held
// particles get none.
[[gnu::always_inline]] inline void kick_particle(Particles& p, std::size_t k, double h) {
  if (p.flags[k] & (kFixed | kPrescribed)) return;
  p.velocity[k] += h * p.force[k] / p.mass[k];
  p.omega[k] += h * p.torque[k] / p.inertia[k];
}

// Zero force and torque of particles [begin, end).
[[gnu::always_inline]] inline void zero_forces(Particles& p, std::size_t begin, std::size_t end) {
  std::fill(p.force.begin() + static_cast<std::ptrdiff_t>(begin), p.force.begin() + static_cast<std::ptrdiff_t>(end), Vec3::Zero());
  std::fill(p.torque.begin() + static_cast<std::ptrdiff_t>(begin), p.torque.begin() + static_cast<std::ptrdiff_t>(end), Vec3::Zero());
}

// to += from and to -= from for a Vec3 stored x, y, z: x and y as one SSE2 pair, z alone, the
// same IEEE additions as Eigen's +=.
[[gnu::always_inline]] inline void add3(double* to, const double* from) {
#if defined(__SSE2__)
  _mm_storeu_pd(to, _mm_add_pd(_mm_loadu_pd(to), _mm_loadu_pd(from)));
#else
  to[0] += from[0], to[1] += from[1];
#endif
  to[2] += from[2];
}
[[gnu::always_inline]] inline void subtract3(double* to, const double* from) {
#if defined(__SSE2__)
  _mm_storeu_pd(to, _mm_sub_pd(_mm_loadu_pd(to), _mm_loadu_pd(from)));
#else
  to[0] -= from[0], to[1] -= from[1];
#endif
  to[2] -= from[2];
}

// Below this many particles everything fits in cache and renumbering would only cost time (and
// move particles that small hand-built scenes address by index).
constexpr std::size_t kReorderMinParticles = 10000;

}  // namespace

struct ContactWorkspace {
  std::vector<ThreadShare> threads;
  SpatialOrder order;
  double order_cell = 1;  // m: the Morton grid, one neighbour-search cell
  PairExclusion bonded;   // the bonded pairs, without contacts when bonded_contacts is off
  // The first half-step's turn per particle: angle, unit axis, rotation quaternion (x, y, z, w).
  std::vector<double> turn_angle, turn_axis, turn_rotation;
  // The largest squared displacement since the neighbour build, found by the last drift; < 0
  // when not known (before the first step), and then the rebuild check finds it itself.
  double drift_moved2 = -1;
  // The drift has zeroed the particles' force and torque (after its kick read them), so the force
  // pass needs no zero fill and no barrier after it.
  bool forces_zeroed = false;

  void prepare_drift(std::size_t n) {
    turn_angle.resize(n);
    turn_axis.resize(3 * n);
    turn_rotation.resize(4 * n);
  }

  // Buffers for `team` threads over n particles; allocates only when the team or n changes.
  void prepare(int team, std::size_t n, std::size_t walls, std::size_t history_stride) {
    if (threads.size() < static_cast<std::size_t>(team)) threads.resize(static_cast<std::size_t>(team));
    for (std::size_t t = 0; t < threads.size(); ++t) {
      ThreadShare& s = threads[t];
      s.block.reserve(history_stride);
      const std::size_t size = t == 0 ? 0 : n;
      if (s.force.size() != size) {
        assign_on_huge_pages(s.force, size, Vec3(Vec3::Zero()));
        assign_on_huge_pages(s.torque, size, Vec3(Vec3::Zero()));
      }
      if (s.block_force.size() != kBondBlock) {
        s.block_force.resize(kBondBlock);
        s.block_torque_i.resize(kBondBlock);
        s.block_torque_j.resize(kBondBlock);
        s.block_energy.resize(kBondBlock);
      }
      if (s.wall_force.size() != walls) {
        s.wall_force.resize(walls);
        s.wall_torque.resize(walls);
        s.wall_stored.resize(walls);
        s.wall_impacts.resize(walls);
      }
    }
  }
};

namespace {

// The bonds checked, each stored with i < j, sorted by first particle and without repeats: for
// locality and a canonical order.
void canonical_bonds(std::vector<std::pair<Index, Index>>& bonds, std::size_t n) {
  for (auto& [a, b] : bonds) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n || a == b)
      throw std::invalid_argument(fmt::format("bond ({}, {}) names a particle that does not exist", a, b));
    if (a > b) std::swap(a, b);
  }
  std::sort(bonds.begin(), bonds.end());
  bonds.erase(std::unique(bonds.begin(), bonds.end()), bonds.end());
}

// Every particle's and wall's material must be one of the scene's.
void check_materials(std::size_t materials, const Particles& p, const std::vector<Wall>& walls) {
  if (materials == 0 || materials > 1u << 15)
    throw std::invalid_argument(fmt::format("{} materials: a scene has 1 to 32768", materials));
  const auto count = static_cast<std::int32_t>(materials);
  if (count == 1) return;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.material[k] < 0 || p.material[k] >= count)
      throw std::invalid_argument(fmt::format("particle {} has material {}, but the scene has materials 0 to {}",
                                              p.id[k], p.material[k], count - 1));
  for (const auto& w : walls)
    if (w.material < 0 || w.material >= count)
      throw std::invalid_argument(fmt::format("wall '{}' has material {}, but the scene has materials 0 to {}", w.name,
                                              w.material, count - 1));
}

// The smallest sphere (the first of that radius), which bounds the contact time step, and the
// largest, which sizes the skin and the Morton grid.
struct RadiusRange {
  double r_min = std::numeric_limits<double>::infinity();
  std::size_t smallest = 0;
  double r_max = 0;
};

RadiusRange radius_range(const Particles& p) {
  RadiusRange out;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.radius[k] < out.r_min) {
      out.r_min = p.radius[k];
      out.smallest = k;
    }
    out.r_max = std::max(out.r_max, p.radius[k]);
  }
  return out;
}

// The contact law's time step limit: over the smallest sphere, or with several materials over
// each material's smallest (lightest) sphere, since the laws differ per material and pair.
TimeStepLimit contact_time_step_limit(const ContactModel& contact, const Particles& p, std::size_t materials,
                                      const RadiusRange& radii) {
  if (materials == 1) return contact.time_step_limit(radii.r_min, density_of(p, radii.smallest));
  std::vector<MaterialExtent> extents(materials);
  for (std::size_t k = 0; k < p.size(); ++k) {
    MaterialExtent& e = extents[static_cast<std::size_t>(p.material[k])];
    if (e.min_radius == 0 || p.radius[k] < e.min_radius) e = {p.radius[k], density_of(p, k)};
  }
  return contact.time_step_limit(extents);
}

// The time step given, or with "auto" (<= 0) the smallest every model states.
double chosen_time_step(double given, const std::vector<TimeStepLimit>& limits) {
  if (!(given <= 0)) return given;
  double dt = std::numeric_limits<double>::infinity();
  for (const auto& l : limits) dt = std::min(dt, l.recommended);
  if (!std::isfinite(dt))
    throw std::invalid_argument("dt = \"auto\" needs a contact or bond model to derive a time step from; set [simulation] dt");
  return dt;
}

}  // namespace

Simulation::Simulation(SimulationSetup setup)
    : particles_(std::move(setup.particles)),
      contact_(setup.contact),
      bond_(setup.bond),
      materials_(static_cast<std::int32_t>(setup.materials)),
      breakage_(setup.breakage),
      bonded_contacts_(setup.bonded_contacts),
      walls_(std::move(setup.walls)),
      gravity_(setup.gravity),
      global_damping_(setup.global_damping),
      exchange_(setup.exchange) {
  const std::size_t n = particles_.size();
  // A sub-domain holds only some of the bonds of its pairs' ends.
  if (!bonded_contacts_ && exchange_)
    throw std::invalid_argument("[simulation] bonded_contacts = false is not available in a decomposed (MPI) run");
  if (!setup.bonds.empty() && !bond_)
    throw std::invalid_argument("the scene has bonds but no bond model: add a [bond] section (e.g. plugin = \"beam_bond\")");
  canonical_bonds(setup.bonds, n);
  bonds_.stride = bond_ ? bond_->state_size() : 0;
  bonds_.keeps_loads = setup.record_bond_loads;
  bonds_.resize(setup.bonds.size());
  for (std::size_t k = 0; k < setup.bonds.size(); ++k) {
    bonds_.i[k] = setup.bonds[k].first;
    bonds_.j[k] = setup.bonds[k].second;
  }
  if (bond_ && bonds_.size() > 0) {
    BondBatch batch = bond_batch();
    bond_->initialize(batch);
  }

  // Time step (docs/explanation/physics.md, "Time step"): every model states its limit; "auto" takes the smallest.
  const RadiusRange radii = radius_range(particles_);
  check_materials(setup.materials, particles_, walls_);
  if (contact_ && n > 0) limits_.push_back(contact_time_step_limit(*contact_, particles_, setup.materials, radii));
  if (bond_ && bonds_.size() > 0) limits_.push_back(bond_->time_step_limit(bond_batch()));
  dt_ = chosen_time_step(setup.dt, limits_);
  const double skin = setup.skin > 0 ? setup.skin : 0.2 * std::max(radii.r_max, 1e-12);
  neighbours_ = std::make_unique<NeighbourList>(skin, contact_ ? contact_->history_size() : 0);
  workspace_ = std::make_unique<ContactWorkspace>();
  workspace_->order_cell = 2 * std::max(radii.r_max, 1e-12) + skin;
  for (auto& w : walls_) {
    if (w.shape != WallShape::Mesh) w.axis.normalize();
    if (w.motion.spins) w.motion.spin_axis.normalize();
    place_wall(w, time_);
  }
  compute_forces();
}

Simulation::~Simulation() = default;

BondBatch Simulation::bond_batch() {
  BondBatch b;
  b.count = bonds_.size();
  b.time = time_;
  b.dt = dt_;
  b.i = bonds_.i.data();
  b.j = bonds_.j.data();
  b.particles = view_of(particles_);
  b.state = bonds_.state.data();
  // Empty unless the run keeps the loads; bond_chunk then points the outputs at its block buffer.
  b.force = bonds_.force.data();
  b.torque_i = bonds_.torque_i.data();
  b.torque_j = bonds_.torque_j.data();
  b.energy = bonds_.energy.data();
  b.broken = bonds_.broken.data();
  b.stress = bonds_.stress.data();
  return b;
}

void Simulation::step() {
  integrate_first_half();
  time_ += dt_;
  ++step_;
  if (exchange_) exchange_->refresh_ghosts(particles_);
  compute_forces(true);
}

void Simulation::run(std::int64_t steps) {
  for (std::int64_t s = 0; s < steps; ++s) step();
}

void Simulation::begin_settling(double duration, double damping, double step) {
  if (!held_walls_.empty()) throw std::logic_error("begin_settling: the simulation is settling already");
  if (!(step > 0)) throw std::invalid_argument("begin_settling: the settling's time step must be positive");
  held_walls_.reserve(walls_.size());
  for (Wall& w : walls_) {
    held_walls_.push_back({w.motion, w.velocity, w.surface_velocity});
    w.motion = WallMotion{};
    w.velocity = w.surface_velocity = Vec3::Zero();
  }
  loading_damping_ = std::exchange(global_damping_, damping);
  loading_dt_ = std::exchange(dt_, step);
  time_ = -duration;
}

void Simulation::shift_wall(std::size_t k, const Vec3& offset) {
  Wall& w = walls_.at(k);
  w.point += offset;
  w.motion.spin_centre += offset;
  neighbours_->invalidate();  // the wall's candidates are found again at the next step
}

void Simulation::end_settling() {
  for (std::size_t k = 0; k < held_walls_.size(); ++k) {
    Wall& w = walls_[k];
    w.motion = std::move(held_walls_[k].motion);
    w.velocity = held_walls_[k].velocity;
    w.surface_velocity = held_walls_[k].surface_velocity;
    place_wall(w, 0.0);
  }
  held_walls_.clear();
  global_damping_ = loading_damping_;
  dt_ = loading_dt_;
  time_ = 0;
  step_ = 0;
}

// Spheres have isotropic inertia: the lab-frame angular velocity is constant over the drift, so the
// exact rotation is one turn of |omega| dt about omega. The kick and drift and the turn run in
// SIMD lanes (drift_lanes.hpp); only the turn's sin and cos, from libm, one particle at a time.
// Each thread also takes its particles' largest displacement for the neighbour list's rebuild
// check while they are in cache: every parallel region costs the waking of the team (~10-15 us
// with OMP_WAIT_POLICY=passive on a virtual machine), several times a step.
void Simulation::integrate_first_half() {
  const std::size_t n = particles_.size();
  const double h = 0.5 * dt_;
  auto& p = particles_;
  auto& ws = *workspace_;
  ws.prepare_drift(n);
  const DriftLanes lanes{p.position.data()->data(), p.velocity.data()->data(), p.omega.data()->data(),
                         p.orientation.data()->coeffs().data(), p.force.data()->data(), p.torque.data()->data(),
                         p.mass.data(), p.inertia.data(), p.flags.data()};
  double* angle = ws.turn_angle.data();
  double* axis = ws.turn_axis.data();
  double* rotation = ws.turn_rotation.data();
  const NeighbourList* list = contact_ ? neighbours_.get() : nullptr;
  double moved2 = 0;
#pragma omp parallel num_threads(team_for(n)) reduction(max : moved2)
  {
    const Range r = range_of(n, omp_get_thread_num(), omp_get_num_threads());
    kick_and_drift(lanes, r.begin, r.end, h, dt_, angle, axis);
    for (std::size_t k = r.begin; k < r.end; ++k) {
      if (!(angle[k] > 0)) continue;
      const Quat turn(Eigen::AngleAxisd(angle[k], Vec3(axis[3 * k], axis[3 * k + 1], axis[3 * k + 2])));
      std::copy_n(turn.coeffs().data(), 4, rotation + 4 * k);
    }
    turn(lanes, r.begin, r.end, angle, rotation);
    if (list) moved2 = std::max(moved2, list->max_displacement2(p, r.begin, r.end));
    zero_forces(p, r.begin, r.end);
  }
  ws.drift_moved2 = list ? moved2 : -1;
  ws.forces_zeroed = true;
  const double t_next = time_ + dt_;  // the time step() reaches
  for (auto& w : walls_) move_wall(w, t_next, dt_);
}

void Simulation::update_neighbours() {
  NeighbourList& list = *neighbours_;
  const double moved2 = std::exchange(workspace_->drift_moved2, -1.0);
  if (!(moved2 >= 0 ? list.needs_rebuild(particles_, walls_, moved2) : list.needs_rebuild(particles_, walls_))) return;
  // Renumber along the Morton curve while the list is rebuilt anyway.
  SpatialOrder& order = workspace_->order;
  if (particles_.size() >= kReorderMinParticles && order.compute(particles_, workspace_->order_cell)) {
    order.apply(particles_, bonds_);
    list.remap(order.new_index());
  }
  const PairExclusion* excluded = nullptr;
  if (!bonded_contacts_) {
    workspace_->bonded.assign(bonds_.i, bonds_.j, particles_.size());
    excluded = &workspace_->bonded;
  }
  list.rebuild(particles_, walls_, excluded);
}

namespace {

// What a force pass adds to each particle once its pair and bond forces are complete.
struct BodyForces {
  bool gravity;      // gravity_ is not zero
  Vec3 g;
  double damping;    // Cundall's local damping fraction
  bool kick;         // the second half-kick of velocity Verlet too
  double h;          // dt / 2
};

// Thread t's particles `own`: the other threads' shares added in thread order (and left zero for
// the next pass); with `body`, gravity, damping and the kick while the forces are in cache (a
// sub-domain adds them after the reactions come back from the other ranks).
[[gnu::always_inline]] inline void sum_shares(Particles& p, std::vector<ThreadShare>& threads, const Range own, int nt,
                                              const BodyForces* body) {
  for (std::size_t k = own.begin; k < own.end; ++k) {
    for (int u = 1; u < nt; ++u) {
      ThreadShare& other = threads[static_cast<std::size_t>(u)];
      p.force[k] += other.force[k];
      p.torque[k] += other.torque[k];
      other.force[k].setZero();
      other.torque[k].setZero();
    }
    if (body) {
      add_body_forces(p, k, body->gravity, body->g, body->damping);
      if (body->kick) kick_particle(p, k, body->h);
    }
  }
}

// The totals of a force pass over the threads' shares.
struct PassTotals {
  double contact_energy = 0, bond_energy = 0;
  std::size_t contacts = 0;
  bool bond_broke = false;
};

// The threads' shares summed in thread order: the totals, the walls' loads, work and impacts,
// and the wall contacts begun.
PassTotals sum_thread_totals(const std::vector<ThreadShare>& threads, int used, const Particles& p, double dt,
                             std::vector<Wall>& walls, std::vector<WallContactStart>& begun) {
  PassTotals totals;
  for (auto& w : walls) {
    w.force.setZero();
    w.torque.setZero();
    w.stored_energy = 0;
  }
  begun.clear();
  for (int t = 0; t < used; ++t) {
    const ThreadShare& share = threads[static_cast<std::size_t>(t)];
    totals.contact_energy += share.contact_energy;
    totals.contacts += share.contacts;
    totals.bond_energy += share.bond_energy;
    totals.bond_broke = totals.bond_broke || share.bond_broke;
    // The particles' whole forces are known now (wall_touch_work). In thread order, without a
    // barrier in the force pass: a wall's contacts are few next to the particles' pairs.
    for (const WallTouch& c : share.wall_touches) walls[c.wall].contact_work -= wall_touch_work(p, c, dt);
    begun.insert(begun.end(), share.wall_begun.begin(), share.wall_begun.end());
    for (std::size_t w = 0; w < walls.size(); ++w) {
      walls[w].force += share.wall_force[w];
      walls[w].torque += share.wall_torque[w];
      walls[w].stored_energy += share.wall_stored[w];
      walls[w].impacts += share.wall_impacts[w];
    }
  }
  return totals;
}

}  // namespace

// One pass over all forces: each thread takes its range of contact pairs and of bonds, computes
// them with one batch call each, and adds the results to its share (see ThreadShare); then each
// thread sums the shares over its range of particles and adds gravity and damping, and with
// `kick` gives its particles the second half-kick of velocity Verlet while their forces are in
// cache (before, a parallel region of its own).
void Simulation::compute_forces(bool kick) {
  auto& p = particles_;
  const std::size_t n = p.size();
  auto& ws = *workspace_;
  std::size_t pairs = 0;
  if (contact_) {
    update_neighbours();
    pairs = neighbours_->size();
  }
  const std::size_t m = bond_ ? bonds_.size() : 0;
  const int team = team_for(n + pairs + m);
  ws.prepare(team, n, walls_.size(), neighbours_->history_stride());
  const BodyForces body{!gravity_.isZero(), gravity_, global_damping_, kick, 0.5 * dt_};
  // A sub-domain's arrays change at ghost refresh and migration after the drift zeroed them.
  const bool zeroed_by_drift = std::exchange(ws.forces_zeroed, false);
  const bool zero_fill = !zeroed_by_drift || exchange_ != nullptr;
  int used = 1;
#pragma omp parallel num_threads(team)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    ThreadShare& share = ws.threads[static_cast<std::size_t>(t)];
    const Range own = range_of(n, t, nt);
    if (zero_fill) zero_forces(p, own.begin, own.end);
    share.start_pass();
    if (t == 0) used = nt;
    // Thread 0 adds into the particles' arrays, which every thread zeroes over its own range.
    if (zero_fill) {
#pragma omp barrier
    }
    Vec3* force = t == 0 ? p.force.data() : share.force.data();
    Vec3* torque = t == 0 ? p.torque.data() : share.torque.data();
    if (contact_) {
      const Range r = range_of(pairs, t, nt);
      contact_chunk(r.begin, r.end, force, torque, t);
    }
    if (m > 0) {
      const Range r = range_of(m, t, nt);
      bond_chunk(r.begin, r.end, force, torque, t);
    }
#pragma omp barrier
    sum_shares(p, ws.threads, own, nt, exchange_ ? nullptr : &body);
  }
  if (exchange_) {  // a sub-domain: the reactions computed on other ranks first
    exchange_->return_reactions(p);
    for (std::size_t k = 0; k < n; ++k) {
      add_body_forces(p, k, body.gravity, body.g, body.damping);
      if (kick) kick_particle(p, k, body.h);
    }
  }
  const PassTotals totals = sum_thread_totals(ws.threads, used, p, dt_, walls_, wall_contacts_begun_);
  if (contact_) {
    contacts_ = totals.contacts;
    contact_energy_ = totals.contact_energy;
  }
  bond_energy_ = totals.bond_energy;
  if (totals.bond_broke) record_broken_bonds();
}

namespace {

// Copies one contact's history. Every shipped model keeps 3 doubles, which a call to memmove
// (what std::copy_n becomes for a run-time length) costs several times over.
void copy_history(const double* from, double* to, std::size_t stride) {
  if (stride == 3) {
    to[0] = from[0];
    to[1] = from[1];
    to[2] = from[2];
  } else {
    std::copy_n(from, stride, to);
  }
}

// The candidates of the tile [k, stop) in pair order into block.pair, with their ends and
// whether they touched before; a pair that touched and is no longer a candidate loses its history
// (the rule per pair: contact_candidates_scalar.hpp). One pass: the test and the compaction as two
// loops over the tile cost ~20 % more instructions.
std::size_t compact_candidates(const Particles& p, NeighbourList& list, std::size_t k, std::size_t stop,
                               ContactArrays& block) {
  static_assert(std::is_same_v<Index, std::int32_t>);
  const CandidateTile tile{list.first().data(),   list.second().data(),   p.position.data()->data(),
                           p.radius.data(),       list.touching().data(), list.history().data(),
                           list.history_stride(), block.pair.data(),      block.i.data(),
                           block.j.data(),        block.touched.data()};
  std::size_t c = 0;
  // Whole groups of 8 pairs in AVX-512 lanes where the CPU has them (contact_candidates.hpp).
  static const bool lanes = candidate_lanes_available();
  if (lanes && stop - k >= 8) {
    const std::size_t groups = (stop - k) / 8;
    c = candidate_groups_avx512(tile, k, groups, c);
    k += 8 * groups;
  }
  for (std::size_t q = k; q < stop; ++q) c = candidate_pair(tile, q, c);
  return c;
}

// Contact slot c's geometry for particle a against wall w; false when it does not touch.
bool wall_geometry(const Particles& p, const Wall& w, Index a, std::size_t c, ContactArrays& block) {
  const double ra = p.radius[a];
  Vec3 n;
  double distance;
  if (!wall_contact(w, p.position[a], ra, n, distance) || distance >= ra) return false;
  const Vec3 arm_a = -distance * n;
  // A spinning or belt wall's surface moves differently from point to point.
  const Vec3 vel_b = w.surface_moves() ? w.surface_velocity_at(p.position[a] + arm_a, n) : w.velocity;
  block.normal[c] = n;
  block.overlap[c] = ra - distance;
  block.velocity[c] = p.velocity[a] + p.omega[a].cross(arm_a) - vel_b;
  block.omega_rel[c] = p.omega[a] - w.angular_velocity();
  block.r_eff[c] = ra;
  block.m_eff[c] = p.mass[a];
  return true;
}

// The geometry of the touching particle pairs among block slots [0, count): 8 slots at a time in
// AVX-512 lanes where the CPU has them (contact_geometry.hpp), the rest one by one by the scalar
// rule (contact_geometry_scalar.hpp). A wall slot in a group of lanes is written again by
// `wall_slot`, whose pair is known to touch.
template <class WallSlot>
void pair_geometry(const Particles& p, ContactArrays& block, std::size_t count, WallSlot&& wall_slot) {
  static const bool lanes = pair_geometry_lanes_available();
  const PairGeometryTile tile{p.position.data()->data(), p.velocity.data()->data(), p.omega.data()->data(),
                              p.radius.data(),            p.mass.data(),             block.i.data(),
                              block.j.data(),             block.normal.data()->data(),
                              block.velocity.data()->data(), block.omega_rel.data()->data(),
                              block.overlap.data(),       block.r_eff.data(),        block.m_eff.data()};
  std::size_t c = 0;
  if (lanes) {
    const std::size_t groups = count / 8;
    pair_geometry_avx512(tile, groups);
    for (c = 0; c < 8 * groups; ++c)
      if (block.j[c] < 0) wall_slot(c);
  }
  for (; c < count; ++c)
    if (block.j[c] >= 0) particle_pair_geometry(tile, c);
}

// Geometry of the touching pairs of the next tile of [k, end) into `block`; pairs that stopped
// touching lose their history. Returns the first pair not looked at. The wall pairs are tested
// (and their geometry made) while the candidates are compacted, so that the particle pairs'
// geometry runs over the final slots in one pass.
std::size_t collect_contacts(const Particles& p, const std::vector<Wall>& walls, NeighbourList& list, std::size_t k,
                             std::size_t end, std::int32_t materials, ContactArrays& block) {
  const std::size_t stop = std::min(end, k + kContactBlock);
  const std::size_t candidates = compact_candidates(p, list, k, stop, block);
  const std::size_t stride = list.history_stride();
  const double* history = list.history().data();
  const auto wall_of = [&](Index b) -> const Wall& { return walls[static_cast<std::size_t>(-1 - b)]; };
  std::size_t c = 0;
  for (std::size_t q = 0; q < candidates; ++q) {
    const std::size_t pair = block.pair[q];
    const Index a = block.i[q], b = block.j[q];
    if (b < 0 && !wall_geometry(p, wall_of(b), a, c, block)) {
      std::fill_n(list.history().data() + pair * stride, stride, 0.0);
      list.touching()[pair] = 0;
      continue;
    }
    block.i[c] = a;
    block.j[c] = b;
    block.pair[c] = pair;
    block.touched[c] = block.touched[q];
    if (materials > 1) block.material_pair[c] = p.material[a] * materials + (b >= 0 ? p.material[b] : wall_of(b).material);
    copy_history(history + pair * stride, block.history.data() + c * stride, stride);
    ++c;
  }
  pair_geometry(p, block, c, [&](std::size_t s) { wall_geometry(p, wall_of(block.j[s]), block.i[s], s, block); });
  block.count = c;
  return stop;
}

void run_model(const ContactModel& model, double dt, bool materials, ContactArrays& block) {
  ContactBatch batch;
  batch.count = block.count;
  batch.dt = dt;
  batch.i = block.i.data();
  batch.j = block.j.data();
  batch.normal = block.normal.data();
  batch.overlap = block.overlap.data();
  batch.velocity = block.velocity.data();
  batch.omega_rel = block.omega_rel.data();
  batch.r_eff = block.r_eff.data();
  batch.m_eff = block.m_eff.data();
  batch.history = block.history.data();
  batch.force = block.force.data();
  batch.couple = block.couple.data();
  batch.energy = block.energy.data();
  batch.material_pair = materials ? block.material_pair.data() : nullptr;
  std::fill_n(batch.force, batch.count, Vec3::Zero());
  std::fill_n(batch.couple, batch.count, Vec3::Zero());
  std::fill_n(batch.energy, batch.count, 0.0);
  model.compute(batch);
}

// The torques of the block's particle pairs: 8 slots at a time in AVX-512 lanes where the CPU has
// them (contact_geometry.hpp), the rest one by one by the scalar rule (contact_geometry_scalar.hpp).
void pair_loads(const Particles& p, ContactArrays& block) {
  static const bool lanes = pair_geometry_lanes_available();
  const PairLoadsTile tile{p.radius.data(),          block.i.data(),         block.j.data(),
                           block.force.data()->data(), block.couple.data()->data(), block.normal.data()->data(),
                           block.overlap.data(),     block.torque_a.data()->data(), block.torque_b.data()->data()};
  std::size_t k = 0;
  if (lanes) {
    const std::size_t groups = block.count / 8;
    pair_loads_avx512(tile, groups);
    k = 8 * groups;
  }
  for (; k < block.count; ++k)
    if (block.j[k] >= 0) particle_pair_loads(tile, k);
}

// The block's forces into this thread's share, in contact order; the history back to the list.
// Returns `energy` plus the block's energies, summed in contact order.
double scatter_contacts(const Particles& p, const std::vector<Wall>& walls, NeighbourList& list,
                        ContactArrays& block, Vec3* force, Vec3* torque, ThreadShare& share, double energy) {
  const std::size_t stride = list.history_stride();
  double* history = list.history().data();
  const double* radius = p.radius.data();
  pair_loads(p, block);
  for (std::size_t k = 0; k < block.count; ++k) {
    const Index a = block.i[k], b = block.j[k];
    const double* f = block.force[k].data();
    const double overlap = block.overlap[k];
    energy += block.energy[k];
    if (b >= 0) {
      add3(force[a].data(), f);
      add3(torque[a].data(), block.torque_a[k].data());
      subtract3(force[b].data(), f);
      add3(torque[b].data(), block.torque_b[k].data());
    } else {
      const Vec3& fv = block.force[k];
      const Vec3& nv = block.normal[k];
      force[a] += fv;
      const Vec3 arm_a = -(radius[a] - overlap) * nv;
      torque[a] += arm_a.cross(fv) + block.couple[k];
      const auto w = static_cast<std::size_t>(-1 - b);
      const Wall& wall = walls[w];
      const Vec3 contact_point = p.position[a] + arm_a;
      const Vec3 pivot = wall.motion.spins ? wall.centre() : Vec3(wall.point + wall.displacement);
      share.wall_force[w] -= fv;
      share.wall_torque[w] += (contact_point - pivot).cross(-fv) - block.couple[k];
      share.wall_touches.push_back({a, w, fv, block.couple[k], arm_a, block.velocity[k], block.omega_rel[k]});
      share.wall_stored[w] += block.energy[k];
      share.wall_impacts[w] += block.touched[k] ^ 1;
      if (!block.touched[k]) share.wall_begun.push_back({a, static_cast<std::int32_t>(w), nv});
    }
    copy_history(block.history.data() + k * stride, history + block.pair[k] * stride, stride);
  }
  return energy;
}

}  // namespace

// The thread's pairs block by block: geometry, model, scatter. The energy is summed in contact
// order across the blocks, so the result does not depend on the block size.
void Simulation::contact_chunk(std::size_t begin, std::size_t end, Vec3* force, Vec3* torque, int thread) {
  ThreadShare& share = workspace_->threads[static_cast<std::size_t>(thread)];
  ContactArrays& block = share.block;
  double energy = 0;
  std::size_t contacts = 0;
  const NeighbourList& list = *neighbours_;
  for (std::size_t k = begin; k < end;) {
    prefetch_pair_ends(particles_, list.first().data(), list.second().data(), neighbours_->touching().data(),
                       std::min(end, k + kContactBlock), std::min(end, k + 2 * kContactBlock), force, torque);
    k = collect_contacts(particles_, walls_, *neighbours_, k, end, materials_, block);
    if (block.count == 0) continue;
    contacts += block.count;
    run_model(*contact_, dt_, materials_ > 1, block);
    energy = scatter_contacts(particles_, walls_, *neighbours_, block, force, torque, share, energy);
  }
  share.contacts = contacts;
  share.contact_energy = energy;
}

// The bond range is run in blocks whose loads go to this thread's block buffer, still in L1 when
// they are added to the particles. Per-bond arrays, unless the run records them, would only be
// written out to memory for nobody to read.
void Simulation::bond_chunk(std::size_t begin, std::size_t end, Vec3* force, Vec3* torque, int thread) {
  constexpr std::size_t kBlock = kBondBlock;
  const bool writes_every_output = bond_->writes_every_output();
  ThreadShare& share = workspace_->threads[static_cast<std::size_t>(thread)];
  bool broke = false;
  double energy = 0;
  for (std::size_t first = begin; first < end; first += kBlock) {
    BondBatch b = bond_batch();
    b.count = std::min(kBlock, end - first);
    b.i += first;
    b.j += first;
    b.state += first * bonds_.stride;
    if (bonds_.keeps_loads) {
      b.force += first;
      b.torque_i += first;
      b.torque_j += first;
      b.energy += first;
    } else {
      b.force = share.block_force.data();
      b.torque_i = share.block_torque_i.data();
      b.torque_j = share.block_torque_j.data();
      b.energy = share.block_energy.data();
    }
    b.broken += first;
    b.stress += first;
    if (!writes_every_output) {
      std::fill_n(b.force, b.count, Vec3::Zero());
      std::fill_n(b.torque_i, b.count, Vec3::Zero());
      std::fill_n(b.torque_j, b.count, Vec3::Zero());
      std::fill_n(b.energy, b.count, 0.0);
    }
    std::fill_n(b.broken, b.count, std::uint8_t{0});
    const std::size_t next = std::min(end, first + 2 * kBlock);
    if (first + kBlock < next)
      prefetch_bond_ends(particles_, b.i + kBlock, b.j + kBlock, next - first - kBlock, force, torque);
    bond_->compute(b);
    // The block's loads into the particles in bond order. The batch's pointers as locals, held in
    // registers (through the struct, GCC reloaded seven of them from the stack for every bond).
    const Index* bi = b.i;
    const Index* bj = b.j;
    std::uint8_t* broken = b.broken;
    const double* f = b.force->data();
    const double* ti = b.torque_i->data();
    const double* tj = b.torque_j->data();
    const double* e = b.energy;
    double* fp = force->data();
    double* tp = torque->data();
    for (std::size_t k = 0; k < b.count; ++k) {
      if (broken[k]) {
        if (breakage_) {
          broke = true;
          continue;  // a bond that fails this step transmits nothing
        }
        broken[k] = 0;
      }
      energy += e[k];
      const std::size_t i = 3 * static_cast<std::size_t>(bi[k]), j = 3 * static_cast<std::size_t>(bj[k]);
      add3(fp + i, f + 3 * k);
      subtract3(fp + j, f + 3 * k);
      add3(tp + i, ti + 3 * k);
      add3(tp + j, tj + 3 * k);
    }
  }
  share.bond_broke = broke;
  share.bond_energy = energy;
}

// Break events in bond order, whatever the thread count; then the broken bonds are dropped.
void Simulation::record_broken_bonds() {
  const auto& p = particles_;
  const std::size_t m = bonds_.size();
  for (std::size_t k = 0; k < m; ++k) {
    if (!bonds_.broken[k]) continue;
    BondBreakEvent e;
    e.time = time_;
    e.step = step_;
    e.id_i = p.id[bonds_.i[k]];
    e.id_j = p.id[bonds_.j[k]];
    e.midpoint = 0.5 * (p.position[bonds_.i[k]] + p.position[bonds_.j[k]]);
    e.stress = bonds_.stress[k];
    events_.push_back(e);
  }
  bonds_broken_ += static_cast<std::int64_t>(bonds_.remove_broken());
  // The failed bonds' pairs may touch: listed from the next force pass on.
  if (!bonded_contacts_ && contact_) neighbours_->invalidate();
}

std::vector<BondBreakEvent> Simulation::take_new_break_events() {
  std::vector<BondBreakEvent> out(events_.begin() + static_cast<std::ptrdiff_t>(events_taken_), events_.end());
  events_taken_ = events_.size();
  return out;
}

Energies Simulation::energies() const {
  Energies e;
  const auto& p = particles_;
  for (std::size_t k = 0; k < p.size(); ++k) {
    e.kinetic += 0.5 * p.mass[k] * p.velocity[k].squaredNorm() + 0.5 * p.inertia[k] * p.omega[k].squaredNorm();
    e.gravity -= p.mass[k] * gravity_.dot(p.position[k]);
  }
  e.bond = bond_energy_;
  e.contact = contact_energy_;
  return e;
}

std::size_t Simulation::contact_count() const { return contacts_; }
std::int64_t Simulation::neighbour_rebuilds() const { return neighbours_->rebuilds(); }

}  // namespace shard
