// The run loop of run_driver.cpp over a DistributedSimulation: the same observers, series rows,
// frames, checkpoints and restart, with every figure of the whole run reduced over the ranks in
// rank order. Every rank writes the run file through MPI-IO (a frame without fragment labels each
// its own rows; a labelled one gathered to rank 0); checkpoints are gathered to rank 0 and written
// there.
#include "shard/driver/distributed_run.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>
#include <omp.h>

#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include "../run_loop_parts.hpp"
#include "../run_restart.hpp"
#include "distributed_health.hpp"
#include "distributed_impacts.hpp"
#include "shard/body_impacts.hpp"
#include "shard/checkpoint.hpp"
#include "shard/driver/load_sensor.hpp"
#include "shard/driver/numerical_health.hpp"
#include "shard/driver/output_folder.hpp"
#include "shard/mpi/distributed_simulation.hpp"
#include "shard/output.hpp"
#include "shard/plugin_host.hpp"
#include "shard/run_file.hpp"
#include "shard/scene.hpp"

namespace shard::driver {
namespace {

using namespace detail;

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// Runs `work` on rank 0 only, then every rank learns whether it failed: a failure is thrown on
// every rank as an OutputError with rank 0's message (the others would otherwise wait for rank 0
// in the next collective call forever).
template <class F>
void on_root(F&& work) {
  std::string error;
  if (world_rank() == 0) {
    try {
      work();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  int size = static_cast<int>(error.size());
  MPI_Bcast(&size, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (size == 0) return;
  error.resize(static_cast<std::size_t>(size));
  MPI_Bcast(error.data(), size, MPI_CHAR, 0, MPI_COMM_WORLD);
  throw OutputError(error);
}

// Runs `work` on every rank (a call of the run file's writer, which every rank makes alike), then
// every rank learns whether one failed: a failure is thrown on every rank as an OutputError with
// the lowest failing rank's message. An error inside one of HDF5's collective calls can still
// leave the other ranks waiting in it (docs/explanation/scaling.md).
template <class F>
void on_all(F&& work) {
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
  int size = static_cast<int>(error.size());
  MPI_Bcast(&size, 1, MPI_INT, first, MPI_COMM_WORLD);
  error.resize(static_cast<std::size_t>(size));
  MPI_Bcast(error.data(), size, MPI_CHAR, first, MPI_COMM_WORLD);
  throw OutputError(error);
}

// The run file shared by the ranks: the MPI-IO driver, run.xmf kept by rank 0.
RunWriterAccess shared_run_file(int rank) {
  RunWriterAccess access;
  access.configure = [](std::int64_t list) {
    if (H5Pset_fapl_mpio(list, MPI_COMM_WORLD, MPI_INFO_NULL) < 0)
      throw OutputError("cannot select HDF5's MPI-IO driver for the run file: is this build's HDF5 the parallel one?");
  };
  access.writes_index = rank == 0;
  return access;
}

void collective_transfer(std::int64_t list) {
  if (H5Pset_dxpl_mpio(list, H5FD_MPIO_COLLECTIVE) < 0)
    throw OutputError("cannot ask HDF5 for collective MPI-IO transfers");
}

// bending::deformation_kinetic_energy over every rank's particles: the kinetic energy less that
// of the rigid-body motion, from moments summed in rank order (about the origin, moved to the
// centre of mass here) instead of a pass over all particles on one rank.
double deformation_kinetic_energy(const mpi::DistributedSimulation& sim) {
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

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

MpiSession::MpiSession() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    int provided = 0;
    // Funneled: only the main thread calls MPI; a rank's OpenMP threads never do.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    initialised_here_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (initialised_here_ && !finalised) MPI_Finalize();
}

void abort_job(const std::string& message) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  const int rank = initialised ? world_rank() : 0;
  std::fprintf(stderr, "shard: error%s: %s\n", rank == 0 ? "" : fmt::format(" (rank {})", rank).c_str(),
               message.c_str());
  std::fflush(stderr);
  if (initialised) MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}

RunResult run_distributed(const RunSpec& spec, const PluginHost& host, const std::vector<RunObserver*>& observers,
                          const RunLog& log_all) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (spec.threads > 0) omp_set_num_threads(spec.threads);
  H5dont_atexit();  // as run_driver.cpp: every file is closed through RAII
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  // Rank 0 speaks for the run.
  const RunLog log = rank == 0 ? log_all : RunLog{};
  auto info = [&](const std::string& line) {
    if (log.info) log.info(line);
  };

  // Every rank reads the restart's files (read-only), so a bad one is refused alike everywhere.
  RunStart start = read_run_start(spec, host, log, [](const std::filesystem::path& checkpoint) {
    require_id_dataset(checkpoint);
    Checkpoint c = read_checkpoint(checkpoint);
    require_ids(c, checkpoint);
    return c;
  });
  const bool restarting = start.restarting;
  const std::optional<Checkpoint>& restart_point = start.restart_point;
  const RunMetadata& old_meta = start.old_meta;
  const Scene& scene = start.scene;
  if (!restarting) on_root([&] { prepare_run_output(spec, scene); });
  // The whole scene on every rank (the generator's packing is not distributed yet): each keeps
  // its part when the DistributedSimulation places it.
  SceneInstance inst = instantiate(scene, host, info);
  std::optional<mpi::DistributedSimulation> dist_slot;
  try {
    if (restart_point)
      dist_slot.emplace(MPI_COMM_WORLD, setup_of(scene, inst), restart_point->simulation);
    else
      dist_slot.emplace(MPI_COMM_WORLD, setup_of(scene, inst));
  } catch (const std::invalid_argument& e) {
    if (restarting)
      throw CheckpointError(fmt::format("cannot continue from {}: {}", checkpoint_path_for(spec.restart).string(),
                                        e.what()));
    throw SceneError(fmt::format("{}: {}", scene.file.string(), e.what()));
  }
  mpi::DistributedSimulation& dist = *dist_slot;
  Simulation& sim = dist.local();  // this rank's share: the run's step, time, dt and walls
  DistributedHealth health(*inst.simulation, scene.gravity);
  DistributedImpacts impacts(inst.simulation->particles());  // first wall contact per body (docs/reference/bodies.md)

  RunResult result;
  result.particles = restart_point ? restart_point->simulation.particles.size() : inst.simulation->particles().size();
  result.bonds_initial = dist.bond_count() + static_cast<std::size_t>(dist.bonds_broken());
  result.dt = dist.dt();
  info(fmt::format("scene {}: {} particles, {} bonds, {} walls, over {} MPI ranks", scene.file.string(),
                   result.particles, result.bonds_initial, sim.walls().size(), ranks));
  RunMetadata meta = run_metadata(scene, inst, host, log);
  meta.notes.emplace_back("mpi_ranks", fmt::format("{}", ranks));
  inst.simulation.reset();  // the whole scene was needed for the baseline and the metadata only

  std::vector<std::string> wall_names;
  for (const auto& w : sim.walls()) wall_names.push_back(w.name);
  const auto series_every = std::max<std::int64_t>(1, std::llround(scene.series_interval / dist.dt()));
  const auto frame_every = std::max<std::int64_t>(1, std::llround(scene.frame_interval / dist.dt()));
  result.output = restarting ? spec.restart : spec.out_dir / scene.output_file;
  const std::filesystem::path checkpoint_file = checkpoint_path_for(result.output);
  // Every rank holds the run file open through MPI-IO and makes every call of the writer alike
  // (the series rows and break events are the same on every rank); a frame's rows are each
  // rank's own (write_frame below).
  std::optional<RunWriter> writer;
  if (restarting) {
    meta = old_meta;
    meta.notes.emplace_back("mpi_ranks_after_restart", fmt::format("{} from step {}", ranks, dist.step_count()));
  }
  if (!restarting) {
    on_all([&] { writer.emplace(result.output, meta, wall_names, shared_run_file(rank)); });
  } else {
    std::filesystem::path moved_aside = spec.restart;
    moved_aside.replace_extension(".interrupted.h5");
    on_root([&] { std::filesystem::rename(spec.restart, moved_aside); });
    try {
      // Every rank reads the interrupted file and writes its prefix alike.
      on_all([&] {
        writer.emplace(result.output, meta, wall_names, shared_run_file(rank));
        const auto copied =
            copy_run_prefix(moved_aside, *writer, *restart_point, {series_every, frame_every}, wall_names);
        writer->flush();
        info(fmt::format("restart: continuing {} from step {} (t = {:.6g} s) on {} ranks; {} frames and the series "
                         "up to it kept",
                         result.output.string(), dist.step_count(), dist.time(), ranks, copied));
      });
    } catch (...) {
      // Put the interrupted run back as it was: a failed restart must not cost the user the run.
      writer.reset();
      MPI_Barrier(MPI_COMM_WORLD);
      if (rank == 0) {
        std::error_code ignored;
        std::filesystem::rename(moved_aside, spec.restart, ignored);
      }
      throw;
    }
    on_root([&] { std::filesystem::remove(moved_aside); });
  }

  std::size_t events_written = restart_point ? restart_point->simulation.events_taken : 0;
  const LoadSensor sensor(scene, sim);
  const Particles no_particles;
  const Bonds no_bonds;
  RunState::Whole whole;
  whole.frame_particles = &no_particles;
  whole.frame_bonds = &no_bonds;
  whole.bonds_broken = dist.bonds_broken();
  whole.bonds_intact = dist.bond_count();
  whole.all_slower_than = [&dist](double speed) { return dist.all_slower_than(speed); };
  RunState state(scene, sim, result, sensor, [&] {
    Checkpoint c;
    c.simulation = dist.gather_state(0, true);
    c.simulation.events_taken = events_written;
    save_loop_state(c, result, state.frames_written, health.state(dist));
    on_root([&] {
      c.arrays.emplace_back("body_impacts", impacts.state());
      write_checkpoint(checkpoint_file, c);
    });
    result.checkpoint = checkpoint_file;
    result.checkpoint_step = dist.step_count();
  });
  state.whole = &whole;
  state.wall_start = wall_start;
  state.restarted = restarting;
  if (restart_point) {
    restore_loop_state(*restart_point, result, state.frames_written);
    health.restore(restart_point->array("health"), rank);
    impacts.restore(restart_point->array("body_impacts"));
    result.restarted_from = dist.step_count();
  }
  auto last_good = [&] { return last_good_state(result); };
  // Every frame is written by all ranks at once, each its own particles and bonds (nothing of it
  // gathered: docs/explanation/scaling.md). A frame the fragment labeller labels (its cadence: [analysis]
  // fragments_every) gathers to rank 0 what the labels need, the particles' ids and masses and the
  // bonds' rows, in the frame's row order; rank 0 labels the whole bond graph and sends each rank
  // the labels of its rows.
  auto write_frame = [&] {
    const int every = scene.fragments_every;
    const bool to_label = every > 0 && state.frames_written % every == 0;
    const mpi::FrameShare share = dist.frame_share();
    Particles label_particles;
    Bonds label_bonds;
    if (to_label) {
      label_particles.id = dist.gather_to_root(share.particles.id);
      label_particles.mass = dist.gather_to_root(share.particles.mass);
      const std::vector<Index> rows = dist.gather_to_root(share.bond_rows);
      for (std::size_t k = 0; k + 1 < rows.size(); k += 2) {
        label_bonds.i.push_back(rows[k]);
        label_bonds.j.push_back(rows[k + 1]);
      }
    }
    whole.frame_particles = &label_particles;
    whole.frame_bonds = &label_bonds;
    state.frame_labels = nullptr;
    for (auto* o : observers) o->before_frame(state);
    FramePart part;
    part.labelled = dist.any_rank(state.frame_labels != nullptr);
    std::vector<Index> labels;
    if (part.labelled)
      labels = dist.scatter_from_root(rank == 0 && state.frame_labels ? *state.frame_labels : std::vector<Index>{},
                                      share.particles.id.size());
    part.fragment_labels = &labels;
    part.configure_transfer = collective_transfer;
    part.particles = &share.particles;
    part.first_row = share.first_row;
    part.total_rows = share.total_rows;
    part.bond_rows = &share.bond_rows;
    part.first_bond = share.first_bond;
    part.total_bonds = share.total_bonds;
    on_all([&] { writer->write_frame_part(dist.step_count(), dist.time(), part); });
    whole.frame_particles = &no_particles;  // the gathered ids and masses go out of scope here
    whole.frame_bonds = &no_bonds;
    ++state.frames_written;
  };
  auto series_row = [&] {
    SeriesRow row;
    row.step = dist.step_count();
    row.time = dist.time();
    const Energies e = dist.energies();
    row.kinetic_energy = e.kinetic;
    row.bond_energy = e.bond;
    row.contact_energy = e.contact;
    whole.bonds_intact = dist.bond_count();
    whole.bonds_broken = dist.bonds_broken();
    row.bonds_intact = static_cast<std::int64_t>(whole.bonds_intact);
    row.bonds_broken = whole.bonds_broken;
    row.contacts = static_cast<std::int64_t>(dist.contact_count());
    // A wall's dissipated work and impacts are counted by each rank for its own contacts.
    std::vector<double> own;
    for (const Wall& w : sim.walls()) own.insert(own.end(), {w.contact_work, static_cast<double>(w.impacts)});
    const std::vector<double> total = dist.sum_over_ranks(own);
    for (std::size_t w = 0; w < sim.walls().size(); ++w) {
      Wall summed = sim.walls()[w];
      summed.contact_work = total[2 * w];
      summed.impacts = static_cast<std::int64_t>(total[2 * w + 1]);
      row.add_wall(summed);
    }
    const auto& events = dist.break_events();
    on_all([&] {
      writer->append_series(row);
      writer->append_break_events(std::vector<BondBreakEvent>(events.begin() + static_cast<std::ptrdiff_t>(events_written),
                                                              events.end()));
    });
    events_written = events.size();
    if (!std::isfinite(e.kinetic)) health.check(dist, last_good());
    record_curve_point(result, dist.time(), sensor.load(sim), sensor.displacement(sim), dist.bonds_broken() == 0,
                       e.bond + e.contact, [&] { return deformation_kinetic_energy(dist); });
    return e;
  };

  LoopHooks loop{[&] { return dist.step_count(); },
                 [&] {
                   dist.step();
                   health.after_step(dist);
                   impacts.update(dist);
                   whole.bonds_broken = dist.bonds_broken();
                 },
                 [&] { health.check(dist, last_good()); },
                 series_row,
                 write_frame,
                 // The stop rules read the run's walls and counts, the same on every rank: they stop
                 // alike. A signal reaches the ranks one by one (SIGINT sent to one, mpirun's SIGTERM
                 // to all at slightly different steps): a stop asked on one stops all here.
                 [&](std::int64_t s) {
                   if (dist.any_rank(state.stop_requested()) && !state.stop_requested())
                     state.request_stop(StopReason::Interrupted,
                                        fmt::format("interrupted (a signal reached another rank) at step {}: "
                                                    "checkpoint written; continue with shard run --restart {}",
                                                    s, result.output.string()));
                 }};
  run_observed_steps(state, observers, scene.duration, dist.dt(), restarting,
                     {series_every, frame_every, spec.health_every}, loop);
  on_all([&] {
    writer->write_body_impacts(impacts.impacts());
    writer->flush();
  });

  result.steps = dist.step_count();
  result.time = dist.time();
  result.bonds_broken = dist.bonds_broken();
  result.final_displacement = sensor.displacement(sim);
  if (!sensor.empty()) result.max_kinetic_to_elastic = kinetic_to_elastic_up_to_peak(result);
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  for (auto* o : observers) o->on_finish(state);
  return result;
}

}  // namespace shard::driver
