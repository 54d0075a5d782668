#include "shard/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "neighbour_list.hpp"
#include "parallel.hpp"

namespace shard {
namespace {

// Per-step contact arrays, sized to the neighbour list and reused (no allocation per step).
struct ContactArrays {
  std::vector<Index> i, j;
  std::vector<std::size_t> pair;
  std::vector<Vec3> normal, velocity, omega_rel, force, couple;
  std::vector<double> overlap, r_eff, m_eff, energy, history;
  void reserve(std::size_t n, std::size_t stride) {
    i.resize(n);
    j.resize(n);
    pair.resize(n);
    normal.resize(n);
    velocity.resize(n);
    omega_rel.resize(n);
    force.resize(n);
    couple.resize(n);
    overlap.resize(n);
    r_eff.resize(n);
    m_eff.resize(n);
    energy.resize(n);
    history.resize(n * stride);
  }
};

double density_of(const Particles& p, std::size_t k) {
  const double r = p.radius[k];
  return p.mass[k] / (4.0 / 3.0 * std::numbers::pi * r * r * r);
}

}  // namespace

struct ContactWorkspace : ContactArrays {};

Simulation::Simulation(SimulationSetup setup)
    : particles_(std::move(setup.particles)),
      contact_(setup.contact),
      bond_(setup.bond),
      breakage_(setup.breakage),
      walls_(std::move(setup.walls)),
      gravity_(setup.gravity),
      global_damping_(setup.global_damping) {
  const std::size_t n = particles_.size();
  if (!setup.bonds.empty() && !bond_)
    throw std::invalid_argument("the scene has bonds but no bond model: add a [bond] section (e.g. plugin = \"beam_bond\")");
  // Bonds sorted by first particle, each stored with i < j, for locality and a canonical order.
  for (auto& [a, b] : setup.bonds) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n || a == b)
      throw std::invalid_argument(fmt::format("bond ({}, {}) names a particle that does not exist", a, b));
    if (a > b) std::swap(a, b);
  }
  std::sort(setup.bonds.begin(), setup.bonds.end());
  setup.bonds.erase(std::unique(setup.bonds.begin(), setup.bonds.end()), setup.bonds.end());
  bonds_.stride = bond_ ? bond_->state_size() : 0;
  bonds_.resize(setup.bonds.size());
  for (std::size_t k = 0; k < setup.bonds.size(); ++k) {
    bonds_.i[k] = setup.bonds[k].first;
    bonds_.j[k] = setup.bonds[k].second;
  }
  if (bond_ && bonds_.size() > 0) {
    BondBatch batch = bond_batch();
    bond_->initialize(batch);
  }

  // Time step (model.md sec. 4): every model states its limit; "auto" takes the smallest.
  double r_min = std::numeric_limits<double>::infinity();
  std::size_t lightest = 0;
  double r_max = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (particles_.radius[k] < r_min) {
      r_min = particles_.radius[k];
      lightest = k;
    }
    r_max = std::max(r_max, particles_.radius[k]);
  }
  if (contact_ && n > 0) limits_.push_back(contact_->time_step_limit(r_min, density_of(particles_, lightest)));
  if (bond_ && bonds_.size() > 0) limits_.push_back(bond_->time_step_limit(bond_batch()));
  dt_ = setup.dt;
  if (dt_ <= 0) {
    dt_ = std::numeric_limits<double>::infinity();
    for (const auto& l : limits_) dt_ = std::min(dt_, l.recommended);
    if (!std::isfinite(dt_))
      throw std::invalid_argument("dt = \"auto\" needs a contact or bond model to derive a time step from; set [simulation] dt");
  }
  const double skin = setup.skin > 0 ? setup.skin : 0.2 * std::max(r_max, 1e-12);
  neighbours_ = std::make_unique<NeighbourList>(skin, contact_ ? contact_->history_size() : 0);
  workspace_ = std::make_unique<ContactWorkspace>();
  for (auto& w : walls_) {
    if (w.shape != WallShape::Mesh) w.axis.normalize();
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
  compute_forces();
  integrate_second_half();
}

void Simulation::run(std::int64_t steps) {
  for (std::int64_t s = 0; s < steps; ++s) step();
}

void Simulation::integrate_first_half() {
  const std::size_t n = particles_.size();
  const double h = 0.5 * dt_;
  auto& p = particles_;
#pragma omp parallel for schedule(static) if (n > 4096)
  for (std::size_t k = 0; k < n; ++k) {
    if (p.flags[k] & kFixed) continue;
    if (!(p.flags[k] & kPrescribed)) {
      p.velocity[k] += h * p.force[k] / p.mass[k];
      p.omega[k] += h * p.torque[k] / p.inertia[k];
    }
    p.position[k] += dt_ * p.velocity[k];
    // Spheres have isotropic inertia: the lab-frame angular velocity is constant over the drift,
    // so the exact rotation is one turn of |omega| dt about omega.
    const double angle = p.omega[k].norm() * dt_;
    if (angle > 0) {
      p.orientation[k] = Quat(Eigen::AngleAxisd(angle, p.omega[k] / p.omega[k].norm())) * p.orientation[k];
      p.orientation[k].normalize();
    }
  }
  for (auto& w : walls_) w.displacement += dt_ * w.velocity;
}

void Simulation::integrate_second_half() {
  const std::size_t n = particles_.size();
  const double h = 0.5 * dt_;
  auto& p = particles_;
#pragma omp parallel for schedule(static) if (n > 4096)
  for (std::size_t k = 0; k < n; ++k) {
    if (p.flags[k] & (kFixed | kPrescribed)) continue;
    p.velocity[k] += h * p.force[k] / p.mass[k];
    p.omega[k] += h * p.torque[k] / p.inertia[k];
  }
}

void Simulation::compute_forces() {
  auto& p = particles_;
  const std::size_t n = p.size();
  std::fill(p.force.begin(), p.force.end(), Vec3::Zero());
  std::fill(p.torque.begin(), p.torque.end(), Vec3::Zero());
  for (auto& w : walls_) {
    w.force.setZero();
    w.torque.setZero();
  }
  if (contact_) apply_contacts();
  if (bond_ && bonds_.size() > 0) apply_bonds();
  apply_gravity();
  if (global_damping_ > 0) {
    // Cundall's local non-viscous damping: opposes the motion with a fraction of the force.
    for (std::size_t k = 0; k < n; ++k) {
      for (int c = 0; c < 3; ++c) {
        const double v = p.velocity[k][c], w = p.omega[k][c];
        p.force[k][c] -= global_damping_ * std::abs(p.force[k][c]) * (v > 0 ? 1 : (v < 0 ? -1 : 0));
        p.torque[k][c] -= global_damping_ * std::abs(p.torque[k][c]) * (w > 0 ? 1 : (w < 0 ? -1 : 0));
      }
    }
  }
}

void Simulation::apply_gravity() {
  if (gravity_.isZero()) return;
  auto& p = particles_;
  const std::size_t n = p.size();
  for (std::size_t k = 0; k < n; ++k) p.force[k] += p.mass[k] * gravity_;
}

void Simulation::apply_contacts() {
  auto& p = particles_;
  neighbours_->update(p, walls_);
  const std::size_t pairs = neighbours_->size();
  const std::size_t stride = neighbours_->history_stride();
  auto& ws = *workspace_;
  if (ws.i.size() < pairs) ws.reserve(pairs + pairs / 4 + 16, stride);
  const auto& first = neighbours_->first();
  const auto& second = neighbours_->second();
  auto& history = neighbours_->history();

  // Geometry of the touching pairs; pairs that stopped touching lose their history.
  std::size_t c = 0;
  for (std::size_t k = 0; k < pairs; ++k) {
    const Index a = first[k], b = second[k];
    const double ra = p.radius[a];
    Vec3 n;
    double overlap;
    Vec3 arm_a, vel_b, omega_b;
    double r_eff, m_eff;
    if (b >= 0) {
      const Vec3 d = p.position[a] - p.position[b];
      const double dist2 = d.squaredNorm();
      const double reach = ra + p.radius[b];
      if (dist2 >= reach * reach || dist2 == 0.0) {
        std::fill_n(history.begin() + static_cast<std::ptrdiff_t>(k * stride), stride, 0.0);
        continue;
      }
      const double dist = std::sqrt(dist2);
      n = d / dist;
      overlap = reach - dist;
      arm_a = -(ra - 0.5 * overlap) * n;
      const Vec3 arm_b = (p.radius[b] - 0.5 * overlap) * n;
      vel_b = p.velocity[b] + p.omega[b].cross(arm_b);
      omega_b = p.omega[b];
      r_eff = ra * p.radius[b] / reach;
      m_eff = p.mass[a] * p.mass[b] / (p.mass[a] + p.mass[b]);
    } else {
      const Wall& w = walls_[static_cast<std::size_t>(-1 - b)];
      double distance;
      if (!wall_contact(w, p.position[a], ra, n, distance) || distance >= ra) {
        std::fill_n(history.begin() + static_cast<std::ptrdiff_t>(k * stride), stride, 0.0);
        continue;
      }
      overlap = ra - distance;
      arm_a = -distance * n;
      vel_b = w.velocity;
      omega_b = Vec3::Zero();
      r_eff = ra;
      m_eff = p.mass[a];
    }
    ws.i[c] = a;
    ws.j[c] = b;
    ws.pair[c] = k;
    ws.normal[c] = n;
    ws.overlap[c] = overlap;
    ws.velocity[c] = p.velocity[a] + p.omega[a].cross(arm_a) - vel_b;
    ws.omega_rel[c] = p.omega[a] - omega_b;
    ws.r_eff[c] = r_eff;
    ws.m_eff[c] = m_eff;
    std::copy_n(history.begin() + static_cast<std::ptrdiff_t>(k * stride), stride,
                ws.history.begin() + static_cast<std::ptrdiff_t>(c * stride));
    ++c;
  }
  contacts_ = c;

  for_each_chunk(c, [&](std::size_t begin, std::size_t end) {
    ContactBatch batch;
    batch.count = end - begin;
    batch.dt = dt_;
    batch.i = ws.i.data() + begin;
    batch.j = ws.j.data() + begin;
    batch.normal = ws.normal.data() + begin;
    batch.overlap = ws.overlap.data() + begin;
    batch.velocity = ws.velocity.data() + begin;
    batch.omega_rel = ws.omega_rel.data() + begin;
    batch.r_eff = ws.r_eff.data() + begin;
    batch.m_eff = ws.m_eff.data() + begin;
    batch.history = ws.history.data() + begin * stride;
    batch.force = ws.force.data() + begin;
    batch.couple = ws.couple.data() + begin;
    batch.energy = ws.energy.data() + begin;
    std::fill_n(batch.force, batch.count, Vec3::Zero());
    std::fill_n(batch.couple, batch.count, Vec3::Zero());
    std::fill_n(batch.energy, batch.count, 0.0);
    contact_->compute(batch);
  });

  // Scatter in contact order: deterministic whatever the thread count.
  double energy = 0;
  for (std::size_t k = 0; k < c; ++k) {
    const Index a = ws.i[k], b = ws.j[k];
    const Vec3& f = ws.force[k];
    const Vec3& n = ws.normal[k];
    const double overlap = ws.overlap[k];
    energy += ws.energy[k];
    p.force[a] += f;
    const Vec3 arm_a = b >= 0 ? Vec3(-(p.radius[a] - 0.5 * overlap) * n) : Vec3(-(p.radius[a] - overlap) * n);
    p.torque[a] += arm_a.cross(f) + ws.couple[k];
    if (b >= 0) {
      const Vec3 arm_b = (p.radius[b] - 0.5 * overlap) * n;
      p.force[b] -= f;
      p.torque[b] += arm_b.cross(-f) - ws.couple[k];
    } else {
      Wall& w = walls_[static_cast<std::size_t>(-1 - b)];
      const Vec3 contact_point = p.position[a] + arm_a;
      w.force -= f;
      w.torque += (contact_point - (w.point + w.displacement)).cross(-f) - ws.couple[k];
    }
    std::copy_n(ws.history.begin() + static_cast<std::ptrdiff_t>(k * stride), stride,
                history.begin() + static_cast<std::ptrdiff_t>(ws.pair[k] * stride));
  }
  contact_energy_ = energy;
}

void Simulation::apply_bonds() {
  auto& p = particles_;
  BondBatch all = bond_batch();
  const std::size_t stride = bonds_.stride;
  for_each_chunk(all.count, [&](std::size_t begin, std::size_t end) {
    BondBatch b = all;
    b.count = end - begin;
    b.i += begin;
    b.j += begin;
    b.state += begin * stride;
    b.force += begin;
    b.torque_i += begin;
    b.torque_j += begin;
    b.energy += begin;
    b.broken += begin;
    b.stress += begin;
    std::fill_n(b.force, b.count, Vec3::Zero());
    std::fill_n(b.torque_i, b.count, Vec3::Zero());
    std::fill_n(b.torque_j, b.count, Vec3::Zero());
    std::fill_n(b.energy, b.count, 0.0);
    std::fill_n(b.broken, b.count, std::uint8_t{0});
    bond_->compute(b);
  });
  bool any_broken = false;
  const std::size_t m = bonds_.size();
  for (std::size_t k = 0; k < m; ++k) {
    if (breakage_ && bonds_.broken[k]) {
      any_broken = true;
      BondBreakEvent e;
      e.time = time_;
      e.step = step_;
      e.id_i = p.id[bonds_.i[k]];
      e.id_j = p.id[bonds_.j[k]];
      e.midpoint = 0.5 * (p.position[bonds_.i[k]] + p.position[bonds_.j[k]]);
      e.stress = bonds_.stress[k];
      events_.push_back(e);
      continue;  // a bond that fails this step transmits nothing
    }
    const Index a = bonds_.i[k], b = bonds_.j[k];
    p.force[a] += bonds_.force[k];
    p.force[b] -= bonds_.force[k];
    p.torque[a] += bonds_.torque_i[k];
    p.torque[b] += bonds_.torque_j[k];
  }
  if (!breakage_) std::fill(bonds_.broken.begin(), bonds_.broken.end(), std::uint8_t{0});
  if (any_broken) bonds_broken_ += static_cast<std::int64_t>(bonds_.remove_broken());
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
  for (double b : bonds_.energy) e.bond += b;
  e.contact = contact_energy_;
  return e;
}

std::size_t Simulation::contact_count() const { return contacts_; }
std::int64_t Simulation::neighbour_rebuilds() const { return neighbours_->rebuilds(); }

}  // namespace shard
