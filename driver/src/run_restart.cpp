#include "run_restart.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "shard/run_file.hpp"

namespace shard {
namespace {

bool on_cadence(std::int64_t step, std::int64_t every) { return step % every == 0; }

void copy_series(const RunFile& old, RunWriter& writer, std::int64_t last_step, std::int64_t every,
                 const std::vector<std::string>& walls) {
  const auto step = old.read_integer_series("step");
  const auto time = old.read_series("time");
  const auto kinetic = old.read_series("kinetic_energy");
  const auto bond = old.read_series("bond_energy");
  const auto contact = old.read_series("contact_energy");
  const auto intact = old.read_integer_series("bonds_intact");
  const auto broken = old.read_integer_series("bonds_broken");
  const auto contacts = old.read_integer_series("contacts");
  // In the writer's order (the scene's): the file lists its wall groups by name.
  const std::vector<std::string> in_file = old.wall_names();
  for (const auto& w : walls)
    if (std::find(in_file.begin(), in_file.end(), w) == in_file.end())
      throw OutputError(fmt::format("the interrupted run file has no series of the wall '{}'; restart with the run "
                                    "file the checkpoint belongs to",
                                    w));
  std::vector<std::vector<Vec3>> force, torque, displacement;
  std::vector<std::vector<double>> impact_energy;
  std::vector<std::vector<std::int64_t>> impacts;
  for (const auto& w : walls) {
    force.push_back(old.read_wall_series(w, "force"));
    torque.push_back(old.read_wall_series(w, "torque"));
    displacement.push_back(old.read_wall_series(w, "displacement"));
    impact_energy.push_back(old.read_wall_impact_energy(w));
    impacts.push_back(old.read_wall_impacts(w));
  }
  std::int64_t expected = 0;  // the uninterrupted run's rows: step 0, then every `every` steps
  for (std::size_t r = 0; r < step.size() && step[r] <= last_step; ++r) {
    if (!on_cadence(step[r], every)) continue;  // the extra row an interrupted run writes at its end
    if (step[r] != expected)
      throw OutputError(fmt::format("the interrupted run file lacks the series row of step {} (next row: step {}); "
                                    "it cannot be continued exactly",
                                    expected, step[r]));
    SeriesRow row;
    row.step = step[r];
    row.time = time[r];
    row.kinetic_energy = kinetic[r];
    row.bond_energy = bond[r];
    row.contact_energy = contact[r];
    row.bonds_intact = intact[r];
    row.bonds_broken = broken[r];
    row.contacts = contacts[r];
    for (std::size_t w = 0; w < walls.size(); ++w) {
      row.wall_force.push_back(force[w].at(r));
      row.wall_torque.push_back(torque[w].at(r));
      row.wall_displacement.push_back(displacement[w].at(r));
      row.wall_impact_energy.push_back(impact_energy[w].at(r));
      row.wall_impacts.push_back(impacts[w].at(r));
    }
    writer.append_series(row);
    expected += every;
  }
  if (expected <= last_step)
    throw OutputError(fmt::format("the interrupted run file holds series rows up to step {} only, the checkpoint is "
                                  "at step {}; it cannot be continued exactly",
                                  expected - every, last_step));
}

}  // namespace

std::int64_t copy_run_prefix(const std::filesystem::path& old_file, RunWriter& writer, const Checkpoint& checkpoint,
                             const RestartCadence& cadence, const std::vector<std::string>& walls) {
  const RunFile old(old_file);
  const SimulationState& s = checkpoint.simulation;
  copy_series(old, writer, s.step, cadence.series_every, walls);
  writer.append_break_events(std::vector<BondBreakEvent>(
      s.events.begin(), s.events.begin() + static_cast<std::ptrdiff_t>(s.events_taken)));
  std::int64_t copied = 0;
  for (const std::size_t k : old.frames()) {
    const FrameData f = old.read_frame(k);
    if (f.step > s.step) break;
    if (!on_cadence(f.step, cadence.frame_every)) continue;
    Particles p;
    p.id = f.id;
    p.position = f.position;
    p.velocity = f.velocity;
    p.omega = f.omega;
    p.radius = f.radius;
    p.material = f.material;
    p.body = f.body;
    p.mass = f.mass;
    Bonds b;
    b.i = f.bond_i;
    b.j = f.bond_j;
    writer.write_frame(f.step, f.time, p, b, f.fragment ? &*f.fragment : nullptr);
    ++copied;
  }
  return copied;
}

}  // namespace shard
