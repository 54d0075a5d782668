#pragma once
// The step loop: neighbour search -> master contact model -> bond model -> body forces ->
// walls -> velocity-Verlet integration. Owns the state; plugins are borrowed.
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "shard/bond_model.hpp"
#include "shard/bonds.hpp"
#include "shard/contact_model.hpp"
#include "shard/domain_exchange.hpp"
#include "shard/particles.hpp"
#include "shard/time_step.hpp"
#include "shard/wall.hpp"

namespace shard {

struct SimulationSetup {
  Particles particles;
  std::vector<std::pair<Index, Index>> bonds;
  const ContactModel* contact = nullptr;  // master model; may be null (bonds only)
  const BondModel* bond = nullptr;        // may be null when there are no bonds
  // Materials (docs/reference/materials.md): with more than one, the contact model has its table
  // (ContactModel::set_materials) and every particle's `material` and wall's `material` lie in
  // [0, materials); with one, every contact uses the one law and the indices are not read.
  std::size_t materials = 1;
  bool breakage = true;                   // false: bonds never fail (elastic calibration)
  // false: a pair joined by an intact bond gets no contact force (its bond alone acts), and its
  // contact starts when the bond fails; true: a bonded pair that also overlaps gets both.
  bool bonded_contacts = true;
  std::vector<Wall> walls;
  Vec3 gravity = Vec3::Zero();
  double dt = 0;                // 0 = auto: min of the models' recommended steps
  double skin = 0;              // Verlet skin, m; 0 = 0.2 * largest radius
  double global_damping = 0;    // numerical damping fraction, off by default
  // Keep every bond's last force, torques and energy in bonds() (tests, post-processing); off,
  // they live only in a per-thread block buffer until they are added to the particles.
  bool record_bond_loads = false;
  // A sub-domain of a decomposed run (domain_exchange.hpp): ghosts refreshed and reactions
  // returned through it. Null: the whole world. Borrowed; must outlive the Simulation.
  DomainExchange* exchange = nullptr;
};

struct Energies {
  double kinetic = 0;      // translational + rotational, J
  double bond = 0;         // elastic energy stored in bonds, J
  double contact = 0;      // elastic energy stored in contacts, J
  double gravity = 0;      // potential energy -m g.x, J
};

// A wall contact that began in the last force pass: the particle touches the wall now and did not
// at the pass before (the contacts the wear indicator's `impacts` counts).
struct WallContactStart {
  Index particle = 0;
  std::int32_t wall = 0;         // index in walls()
  Vec3 normal = Vec3::Zero();    // unit, from the wall towards the particle
};

class NeighbourList;
struct ContactWorkspace;
struct SimulationState;

class Simulation {
 public:
  explicit Simulation(SimulationSetup setup);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  void step();
  void run(std::int64_t steps);

  // Settling before the loading ([simulation] settle_time): a lab's specimen rests on its supports
  // under its own weight before the pins move. begin_settling holds every wall where it is, sets
  // Cundall damping `damping` and the time step `step`, and puts the clock at -duration; the caller
  // steps up to t = 0, then end_settling gives the walls their motion and the scene's damping and
  // step back and restarts the clock and the step count at 0, so profiles, ramps and outputs run as
  // from a body that was at rest.
  void begin_settling(double duration, double damping, double step);
  void end_settling();
  // Moves wall k's geometry by `offset` (its point, and the centre it spins about): a pin seated
  // on the settled specimen. Its displacement stays what it was; a checkpoint keeps the new point.
  void shift_wall(std::size_t k, const Vec3& offset);

  double time() const { return time_; }
  std::int64_t step_count() const { return step_; }
  double dt() const { return dt_; }
  const std::vector<TimeStepLimit>& time_step_limits() const { return limits_; }

  Particles& particles() { return particles_; }
  const Particles& particles() const { return particles_; }
  const Bonds& bonds() const { return bonds_; }
  std::vector<Wall>& walls() { return walls_; }
  const std::vector<Wall>& walls() const { return walls_; }
  std::size_t contact_count() const;
  std::int64_t bonds_broken() const { return bonds_broken_; }
  // Events since the last call (the output takes them), and all of them.
  std::vector<BondBreakEvent> take_new_break_events();
  const std::vector<BondBreakEvent>& break_events() const { return events_; }
  Energies energies() const;
  // The wall contacts begun in the last force pass, in no fixed order (empty without a contact
  // model: walls then touch nothing). The run driver takes the bodies' first impacts from them.
  const std::vector<WallContactStart>& wall_contacts_begun() const { return wall_contacts_begun_; }
  std::int64_t neighbour_rebuilds() const;
  // Checkpoint/restart (simulation_state.cpp): import_state continues bit-identically from an
  // exported state; the models, walls' geometry and settings come from this Simulation's setup.
  SimulationState export_state() const;
  void import_state(const SimulationState& state);
  // The same without copies: take_state moves the state out (this Simulation then steps again only
  // after an import_state), so a decomposed run's re-partition (mpi/) edits its particles, bonds
  // and contact history in place and moves them back.
  SimulationState take_state();
  void import_state(SimulationState&& state);

 private:
  // Everything of the state but the particle, bond, event and neighbour arrays (export_state
  // copies those, take_state moves them).
  SimulationState state_without_arrays() const;
  // With `kick`, the second half-kick of the step is made in the same pass (a parallel region less).
  void compute_forces(bool kick = false);
  void integrate_first_half();
  void update_neighbours();
  // Thread `thread`'s part of the force pass (simulation.cpp): pairs or bonds [begin, end),
  // results added to force and torque.
  void contact_chunk(std::size_t begin, std::size_t end, Vec3* force, Vec3* torque, int thread);
  void bond_chunk(std::size_t begin, std::size_t end, Vec3* force, Vec3* torque, int thread);
  void record_broken_bonds();
  BondBatch bond_batch();

  Particles particles_;
  Bonds bonds_;
  const ContactModel* contact_;
  const BondModel* bond_;
  std::int32_t materials_ = 1;
  bool breakage_;
  bool bonded_contacts_;
  std::vector<Wall> walls_;
  Vec3 gravity_;
  double dt_ = 0;
  double global_damping_ = 0;
  double time_ = 0;
  std::int64_t step_ = 0;
  std::int64_t bonds_broken_ = 0;
  std::vector<TimeStepLimit> limits_;
  std::unique_ptr<NeighbourList> neighbours_;
  std::unique_ptr<ContactWorkspace> workspace_;
  std::size_t contacts_ = 0;
  std::vector<BondBreakEvent> events_;
  std::size_t events_taken_ = 0;
  std::vector<WallContactStart> wall_contacts_begun_;
  double contact_energy_ = 0;
  double bond_energy_ = 0;
  DomainExchange* exchange_ = nullptr;
  // While settling: each wall's motion, velocity and surface velocity, and the scene's damping.
  struct HeldWall {
    WallMotion motion;
    Vec3 velocity, surface_velocity;
  };
  std::vector<HeldWall> held_walls_;
  double loading_damping_ = 0;
  double loading_dt_ = 0;
};

}  // namespace shard
