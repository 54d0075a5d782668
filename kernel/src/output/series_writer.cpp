#include "series_writer.hpp"

namespace shard {

namespace {

const double* flat(const std::vector<Vec3>& v) { return v.empty() ? nullptr : v.front().data(); }

}  // namespace

SeriesWriter::SeriesWriter(hid_t file, const std::vector<std::string>& wall_names,
                           std::size_t block_rows)
    : block_rows_(block_rows) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 arrays are written as [n,3] doubles");
  h5::Handle series = h5::create_group(file, "series");
  // Chunks of a few thousand rows: large enough that a long run does not index millions of
  // chunks, small enough that a short run wastes little space.
  const std::size_t chunk = 4096;
  step_column_ = h5::make_column<std::int64_t>(series.get(), "step", 0, chunk);
  time_column_ = h5::make_column<double>(series.get(), "time", 0, chunk);
  kinetic_column_ = h5::make_column<double>(series.get(), "kinetic_energy", 0, chunk);
  bond_column_ = h5::make_column<double>(series.get(), "bond_energy", 0, chunk);
  contact_column_ = h5::make_column<double>(series.get(), "contact_energy", 0, chunk);
  intact_column_ = h5::make_column<std::int64_t>(series.get(), "bonds_intact", 0, chunk);
  broken_column_ = h5::make_column<std::int64_t>(series.get(), "bonds_broken", 0, chunk);
  contacts_column_ = h5::make_column<std::int64_t>(series.get(), "contacts", 0, chunk);
  for (auto* v : {&step_, &intact_, &broken_, &contacts_}) v->reserve(block_rows);
  for (auto* v : {&time_, &kinetic_, &bond_, &contact_}) v->reserve(block_rows);

  h5::Handle walls = h5::create_group(series.get(), "walls");
  walls_.reserve(wall_names.size());
  for (const std::string& name : wall_names) {
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
      throw OutputError("wall name '" + name +
                        "' cannot name an HDF5 group: use a non-empty name without '/'");
    h5::Handle group = h5::create_group(walls.get(), name);
    WallColumns& wall = walls_.emplace_back();
    wall.force = h5::make_column<double>(group.get(), "force", 3, chunk);
    wall.torque = h5::make_column<double>(group.get(), "torque", 3, chunk);
    wall.displacement = h5::make_column<double>(group.get(), "displacement", 3, chunk);
    wall.impact_energy = h5::make_column<double>(group.get(), "impact_energy", 0, chunk);
    wall.impacts = h5::make_column<std::int64_t>(group.get(), "impacts", 0, chunk);
    for (auto* v : {&wall.force_rows, &wall.torque_rows, &wall.displacement_rows})
      v->reserve(block_rows);
    wall.impact_energy_rows.reserve(block_rows);
    wall.impacts_rows.reserve(block_rows);
  }
}

void SeriesWriter::append(const SeriesRow& row) {
  const std::size_t n = walls_.size();
  if (row.wall_force.size() != n || row.wall_torque.size() != n ||
      row.wall_displacement.size() != n || row.wall_impact_energy.size() != n ||
      row.wall_impacts.size() != n)
    throw OutputError("series row at step " + std::to_string(row.step) + " has " +
                      std::to_string(row.wall_force.size()) + " wall forces, " +
                      std::to_string(row.wall_torque.size()) + " torques, " +
                      std::to_string(row.wall_displacement.size()) + " displacements, " +
                      std::to_string(row.wall_impact_energy.size()) + " impact energies and " +
                      std::to_string(row.wall_impacts.size()) +
                      " impact counts; the run file was opened with " + std::to_string(n) +
                      " walls (SeriesRow::add_wall fills all five)");
  step_.push_back(row.step);
  time_.push_back(row.time);
  kinetic_.push_back(row.kinetic_energy);
  bond_.push_back(row.bond_energy);
  contact_.push_back(row.contact_energy);
  intact_.push_back(row.bonds_intact);
  broken_.push_back(row.bonds_broken);
  contacts_.push_back(row.contacts);
  for (std::size_t w = 0; w < n; ++w) {
    walls_[w].force_rows.push_back(row.wall_force[w]);
    walls_[w].torque_rows.push_back(row.wall_torque[w]);
    walls_[w].displacement_rows.push_back(row.wall_displacement[w]);
    walls_[w].impact_energy_rows.push_back(row.wall_impact_energy[w]);
    walls_[w].impacts_rows.push_back(row.wall_impacts[w]);
  }
}

void SeriesWriter::write() {
  const std::size_t rows = step_.size();
  if (rows == 0) return;
  step_column_.append(step_.data(), rows);
  time_column_.append(time_.data(), rows);
  kinetic_column_.append(kinetic_.data(), rows);
  bond_column_.append(bond_.data(), rows);
  contact_column_.append(contact_.data(), rows);
  intact_column_.append(intact_.data(), rows);
  broken_column_.append(broken_.data(), rows);
  contacts_column_.append(contacts_.data(), rows);
  for (WallColumns& wall : walls_) {
    wall.force.append(flat(wall.force_rows), rows);
    wall.torque.append(flat(wall.torque_rows), rows);
    wall.displacement.append(flat(wall.displacement_rows), rows);
    wall.impact_energy.append(wall.impact_energy_rows.data(), rows);
    wall.impacts.append(wall.impacts_rows.data(), rows);
    wall.force_rows.clear();
    wall.torque_rows.clear();
    wall.displacement_rows.clear();
    wall.impact_energy_rows.clear();
    wall.impacts_rows.clear();
  }
  for (auto* v : {&step_, &intact_, &broken_, &contacts_}) v->clear();
  for (auto* v : {&time_, &kinetic_, &bond_, &contact_}) v->clear();
}

}  // namespace shard
