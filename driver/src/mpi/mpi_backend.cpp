#include "mpi_backend.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "shard/checkpoint.hpp"
#include "shard/output.hpp"

namespace shard::driver::detail {
namespace {

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// Runs `work` on rank 0 only, then every rank learns whether it failed: a failure is thrown on
// every rank as an OutputError with rank 0's message (the others would otherwise wait for rank 0
// in the next collective call forever).
// Rank `root`'s `v` (a vector of plain values, or a string) on every rank.
template <class Contiguous>
void broadcast(Contiguous& v, int root = 0) {
  unsigned long long size = v.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, root, MPI_COMM_WORLD);
  v.resize(static_cast<std::size_t>(size));
  const std::size_t bytes = v.size() * sizeof(typename Contiguous::value_type);
  if (bytes > static_cast<std::size_t>(INT_MAX)) throw OutputError("more than 2 GiB cannot go out in one broadcast");
  MPI_Bcast(v.data(), static_cast<int>(bytes), MPI_BYTE, root, MPI_COMM_WORLD);
}

void run_on_root(const std::function<void()>& work) {
  std::string error;
  if (world_rank() == 0) {
    try {
      work();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  broadcast(error);
  if (!error.empty()) throw OutputError(error);
}

// Runs `work` on every rank (a call of the run file's writer, which every rank makes alike), then
// every rank learns whether one failed: a failure is thrown on every rank as an OutputError with
// the lowest failing rank's message. An error inside one of HDF5's collective calls can still
// leave the other ranks waiting in it (docs/explanation/scaling.md).
void run_on_all(const std::function<void()>& work) {
  std::string error;
  try {
    work();
  } catch (const std::exception& e) {
    error = e.what();
  }
  const int mine = error.empty() ? INT_MAX : world_rank();
  int first = INT_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == INT_MAX) return;
  broadcast(error, first);
  throw OutputError(error);
}

// A file every rank writes at once: HDF5's MPI-IO driver on its access list.
void use_mpi_io(std::int64_t list) {
  if (H5Pset_fapl_mpio(list, MPI_COMM_WORLD, MPI_INFO_NULL) < 0)
    throw OutputError("cannot select HDF5's MPI-IO driver: is this build's HDF5 the parallel one?");
}

// The run file shared by the ranks: the MPI-IO driver, run.xmf kept by rank 0.
RunWriterAccess shared_run_file(int rank) {
  RunWriterAccess access;
  access.configure = use_mpi_io;
  access.writes_index = rank == 0;
  return access;
}

void collective_transfer(std::int64_t list) {
  if (H5Pset_dxpl_mpio(list, H5FD_MPIO_COLLECTIVE) < 0)
    throw OutputError("cannot ask HDF5 for collective MPI-IO transfers");
}

// Rank 0's values of the loop's numbers and arrays on every rank: a file written by every rank
// must be given the same attributes and shared tables by each.
void same_as_root(Checkpoint& c) {
  std::vector<double> numbers;
  for (const auto& [name, value] : c.numbers) numbers.push_back(value);
  MPI_Bcast(numbers.data(), static_cast<int>(numbers.size()), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  for (std::size_t k = 0; k < numbers.size(); ++k) c.numbers[k].second = numbers[k];
  for (auto& [name, values] : c.arrays) broadcast(values);
}

// Until rank 0 arrives: the others wait without spinning (a rank in a blocking MPI call polls
// at full speed and would take a core from rank 0's work on a shared machine).
void wait_for_root() {
  MPI_Request arrived;
  MPI_Ibarrier(MPI_COMM_WORLD, &arrived);
  for (int done = 0; !done;) {
    MPI_Test(&arrived, &done, MPI_STATUS_IGNORE);
    if (!done) usleep(2000);
  }
}

// Rank 0's strings on every rank (names: no string holds a NUL).
void broadcast(std::vector<std::string>& v) {
  std::vector<char> text;
  for (const std::string& s : v) text.insert(text.end(), s.c_str(), s.c_str() + s.size() + 1);
  broadcast(text);
  v.clear();
  for (auto at = text.begin(); at != text.end();) {
    const auto end = std::find(at, text.end(), '\0');
    v.emplace_back(at, end);
    at = end == text.end() ? end : end + 1;
  }
}

// Rank 0's figures of the whole scene on every rank: a few numbers and names, no particle.
void broadcast(WholeScene& w) {
  std::vector<double> numbers = {static_cast<double>(w.particles), w.dt, static_cast<double>(w.bodies.bodies),
                                 w.bodies.known ? 1.0 : 0.0, w.energy0, w.potential0, w.energy_scale,
                                 static_cast<double>(w.limits.size())};
  std::vector<std::string> names;
  for (const auto& l : w.limits) {
    names.push_back(l.name);
    numbers.insert(numbers.end(), {l.critical, l.recommended});
  }
  for (const auto& [name, value] : w.quality) {
    names.push_back(name);
    numbers.push_back(value);
  }
  broadcast(numbers);
  broadcast(names);
  w.particles = static_cast<std::size_t>(numbers[0]);
  w.dt = numbers[1];
  w.bodies = {static_cast<std::size_t>(numbers[2]), numbers[3] != 0};
  w.energy0 = numbers[4];
  w.potential0 = numbers[5];
  w.energy_scale = numbers[6];
  w.limits.resize(static_cast<std::size_t>(numbers[7]));
  w.quality.resize(names.size() - w.limits.size());
  std::size_t at = 8;
  for (std::size_t k = 0; k < w.limits.size(); ++k, at += 2) w.limits[k] = {names[k], numbers[at], numbers[at + 1]};
  for (std::size_t k = 0; k < w.quality.size(); ++k, ++at) w.quality[k] = {names[w.limits.size() + k], numbers[at]};
}

// analysis::deformation_kinetic_energy over every rank's particles: the kinetic energy less that
// of the rigid-body motion, from moments summed in rank order (about the origin, moved to the
// centre of mass here) instead of a pass over all particles on one rank.
double deformation_kinetic_energy_over_ranks(const mpi::DistributedSimulation& sim) {
  const Particles& p = sim.local().particles();
  std::vector<double> m(20, 0.0);  // mass, m x, m v, kinetic, m x × v + I w, inertia about the origin
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!sim.owns(k)) continue;
    const double mk = p.mass[k];
    const Vec3& x = p.position[k];
    const Vec3& v = p.velocity[k];
    const Vec3 l = mk * x.cross(v) + p.inertia[k] * p.omega[k];
    const Mat3 j = mk * (x.squaredNorm() * Mat3::Identity() - x * x.transpose()) + p.inertia[k] * Mat3::Identity();
    m[0] += mk;
    for (int a = 0; a < 3; ++a) {
      m[1 + static_cast<std::size_t>(a)] += mk * x[a];
      m[4 + static_cast<std::size_t>(a)] += mk * v[a];
      m[8 + static_cast<std::size_t>(a)] += l[a];
      for (int b = 0; b < 3; ++b) m[11 + static_cast<std::size_t>(3 * a + b)] += j(a, b);
    }
    m[7] += 0.5 * (mk * v.squaredNorm() + p.inertia[k] * p.omega[k].squaredNorm());
  }
  const std::vector<double> s = sim.sum_over_ranks(m);
  const double mass = s[0];
  if (!(mass > 0)) return 0;
  const Vec3 centre = Vec3(s[1], s[2], s[3]) / mass;
  const Vec3 v_centre = Vec3(s[4], s[5], s[6]) / mass;
  // About the centre of mass: L_c = L_0 - M c × v_c; J_c = J_0 - M (|c|^2 1 - c c^T).
  const Vec3 angular = Vec3(s[8], s[9], s[10]) - mass * centre.cross(v_centre);
  Mat3 inertia;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) inertia(a, b) = s[11 + static_cast<std::size_t>(3 * a + b)];
  inertia -= mass * (centre.squaredNorm() * Mat3::Identity() - centre * centre.transpose());
  const Vec3 omega = inertia.ldlt().solve(angular);
  const double rigid = 0.5 * mass * v_centre.squaredNorm() + 0.5 * omega.dot(angular);
  return std::max(0.0, s[7] - rigid);
}

// A checkpoint this build can continue from on any rank count: particles named by unique ids.
void require_ids(const Checkpoint& c, const std::filesystem::path& file) {
  const Particles& p = c.simulation.particles;
  std::vector<Index> ids = p.id;
  std::sort(ids.begin(), ids.end());
  const bool unique = std::adjacent_find(ids.begin(), ids.end()) == ids.end();
  if (p.id.size() != p.size() || !unique)
    throw CheckpointError(fmt::format(
        "{}: the checkpoint's particles carry no unique ids (/particles/id), which a decomposed run needs to place "
        "them on the ranks: continue it with the serial build (shard run --restart without mpirun), or start the "
        "run again from its scene",
        file.string()));
}

// Before read_checkpoint: a checkpoint without /particles/id is refused with what to do, not
// with the HDF5 library's missing-dataset error.
void require_id_dataset(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) return;  // read_checkpoint names a missing file
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) return;  // read_checkpoint names an unreadable file
  const bool has = H5Lexists(f, "particles", H5P_DEFAULT) > 0 && H5Lexists(f, "particles/id", H5P_DEFAULT) > 0;
  H5Fclose(f);
  if (!has)
    throw CheckpointError(fmt::format(
        "{}: the checkpoint holds no particle ids (/particles/id), which a decomposed run needs to place the "
        "particles on the ranks: continue it with the build that wrote it (without mpirun), or start the run again "
        "from its scene",
        file.string()));
}

}  // namespace

MpiBackend::MpiBackend() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
  whole_.label_fragments = [this](std::vector<Index>& labels, std::vector<std::size_t>& sizes) {
    mpi::FragmentLabels f = dist_->label_fragments();
    labels = std::move(f.labels);
    sizes = std::move(f.sizes);
  };
}

Checkpoint MpiBackend::read_restart(const std::filesystem::path& checkpoint) const {
  require_id_dataset(checkpoint);
  Checkpoint c = read_checkpoint(checkpoint);
  require_ids(c, checkpoint);
  return c;
}

void MpiBackend::on_root(const std::function<void()>& work) const { run_on_root(work); }
void MpiBackend::on_all(const std::function<void()>& work) const { run_on_all(work); }
void MpiBackend::barrier() const { MPI_Barrier(MPI_COMM_WORLD); }
RunWriterAccess MpiBackend::run_file_access() const { return shared_run_file(rank_); }

// Rank 0 generates the scene and builds it whole while the others wait without spinning (the
// generation is paid once, not once per rank: docs/explanation/scaling.md); its failure is the
// scene's on every rank. The others build the models alone: the first partition sends them their
// particles and bonds, and the whole scene's figures come from rank 0.
ScenePart MpiBackend::instantiate(const Scene& scene, const PluginHost& host,
                                  const std::function<void(const std::string&)>& log) const {
  ScenePart part;
  std::exception_ptr failure;
  std::vector<char> error;
  if (rank_ == 0) {
    try {
      part.instance = shard::instantiate(scene, host, log);
      part.whole = whole_scene_of(part.instance);
    } catch (const std::exception& e) {
      failure = std::current_exception();
      const std::string what = *e.what() ? e.what() : "the scene could not be instantiated on rank 0";
      error.assign(what.begin(), what.end());
    }
  }
  wait_for_root();
  broadcast(error);
  if (failure) std::rethrow_exception(failure);
  if (!error.empty()) throw SceneError(std::string(error.begin(), error.end()));
  broadcast(part.whole);
  if (rank_ != 0) part.instance = instantiate_models(scene, host, log);
  return part;
}

// Rank 0 holds the whole scene, the others none: the first partition sends every particle and
// bond to its owner. A restart places the checkpoint's particles; the scene gives the models.
void MpiBackend::start(const Scene& scene, ScenePart& part, const SimulationState* from) {
  SceneInstance& inst = part.instance;
  const bool whole_here = inst.simulation && !from;
  SimulationSetup setup = whole_here ? setup_of(scene, inst) : setup_without_particles(scene, inst, part.whole.dt);
  inst.simulation.reset();
  if (from)
    dist_.emplace(MPI_COMM_WORLD, std::move(setup), *from);
  else
    dist_.emplace(MPI_COMM_WORLD, std::move(setup), mpi::DistributedSimulation::ScatteredScene{});
  events_written_ = from ? from->events_taken : 0;
  whole_.bonds_broken = dist_->bonds_broken();
  whole_.bonds_intact = dist_->bond_count();
  whole_.all_slower_than = [this](double speed) { return dist_->all_slower_than(speed); };
}

void MpiBackend::add_notes(RunMetadata& meta, bool restarting) const {
  if (restarting)
    meta.notes.emplace_back("mpi_ranks_after_restart", fmt::format("{} from step {}", ranks_, dist_->step_count()));
  else
    meta.notes.emplace_back("mpi_ranks", fmt::format("{}", ranks_));
}

std::string MpiBackend::where() const { return fmt::format(", over {} MPI ranks", ranks_); }

void MpiBackend::step() {
  dist_->step();
  whole_.bonds_broken = dist_->bonds_broken();
  begun_.clear();
  for (const auto& c : dist_->wall_contacts_begun()) begun_.push_back({c.id, c.body, c.wall, c.normal});
}

std::size_t MpiBackend::bond_count() {
  whole_.bonds_intact = dist_->bond_count();
  return whole_.bonds_intact;
}

std::vector<BondBreakEvent> MpiBackend::take_new_break_events() {
  const auto& events = dist_->break_events();
  std::vector<BondBreakEvent> fresh(events.begin() + static_cast<std::ptrdiff_t>(events_written_), events.end());
  events_written_ = events.size();
  return fresh;
}

// Every rank writes its share of the checkpoint into the temporary file at once (MPI-IO, the
// serial layout); rank 0 then flushes it to disk and renames it over the previous one, as the
// serial writer does, once every rank's part is in: a kill before the rename leaves the previous
// checkpoint whole.
void MpiBackend::write_checkpoint(Checkpoint& loop, const std::filesystem::path& file) const {
  same_as_root(loop);
  mpi::StateShare share = dist_->state_share(true);
  share.state.events_taken = events_written_;
  loop.simulation = std::move(share.state);
  CheckpointShare part;
  part.checkpoint = &loop;
  part.particles = share.particles;
  part.bonds = share.bonds;
  part.contacts = share.contacts;
  part.writes_shared = rank_ == 0;
  part.configure = use_mpi_io;
  part.configure_transfer = collective_transfer;
  const std::filesystem::path temporary = checkpoint_temporary_for(file);
  try {
    run_on_all([&] { write_checkpoint_share(temporary, part); });
  } catch (const std::exception&) {
    run_on_root([&] { std::filesystem::remove(temporary); });
    throw;
  }
  run_on_root([&] { publish_checkpoint(temporary, file); });
}

double MpiBackend::deformation_kinetic_energy() const { return deformation_kinetic_energy_over_ranks(*dist_); }

// Every frame is written by all ranks at once, each its own particles and bonds (nothing of it
// gathered: docs/explanation/scaling.md). The fragment labeller labels a frame through
// whole_.label_fragments: a distributed union-find, each rank's labels for its own rows.
void MpiBackend::write_frame(RunWriter& writer, RunState& state, const std::function<void()>& before_frame) {
  const mpi::FrameShare share = dist_->frame_share();
  state.frame_labels = nullptr;
  before_frame();
  FramePart part;
  part.labelled = dist_->any_rank(state.frame_labels != nullptr);
  if (part.labelled && (!state.frame_labels || state.frame_labels->size() != share.particles.id.size()))
    throw std::logic_error("a decomposed frame's fragment labels do not match this rank's rows");
  part.fragment_labels = state.frame_labels;
  part.configure_transfer = collective_transfer;
  part.particles = &share.particles;
  part.first_row = share.first_row;
  part.total_rows = share.total_rows;
  part.bond_rows = &share.bond_rows;
  part.first_bond = share.first_bond;
  part.total_bonds = share.total_bonds;
  on_all([&] { writer.write_frame_part(dist_->step_count(), dist_->time(), part); });
}

}  // namespace shard::driver::detail
