#include "break_event_writer.hpp"

namespace shard {

BreakEventWriter::BreakEventWriter(hid_t file, std::size_t block_rows) : block_rows_(block_rows) {
  h5::Handle events = h5::create_group(file, "events");
  h5::Handle breaks = h5::create_group(events.get(), "bond_breaks");
  const hid_t g = breaks.get();
  const std::size_t chunk = 1024;
  time_column_ = h5::make_column<double>(g, "time", 0, chunk);
  step_column_ = h5::make_column<std::int64_t>(g, "step", 0, chunk);
  id_i_column_ = h5::make_column<Index>(g, "id_i", 0, chunk);
  id_j_column_ = h5::make_column<Index>(g, "id_j", 0, chunk);
  midpoint_column_ = h5::make_column<double>(g, "midpoint", 3, chunk);
  sigma_vm_column_ = h5::make_column<double>(g, "sigma_vm", 0, chunk);
  sigma_axial_column_ = h5::make_column<double>(g, "sigma_axial", 0, chunk);
  tau_column_ = h5::make_column<double>(g, "tau", 0, chunk);
  tension_column_ = h5::make_column<double>(g, "tension", 0, chunk);
  bending_column_ = h5::make_column<double>(g, "bending", 0, chunk);
  shear_column_ = h5::make_column<double>(g, "shear", 0, chunk);
  torsion_column_ = h5::make_column<double>(g, "torsion", 0, chunk);
  mode_column_ = h5::make_column<std::uint8_t>(g, "mode", 0, chunk);
  h5::write_attribute(g, "mode_values", std::string("1 tension, 2 bending, 3 shear, 4 torsion"));
}

void BreakEventWriter::append(const std::vector<BondBreakEvent>& events) {
  for (const BondBreakEvent& e : events) {
    time_.push_back(e.time);
    step_.push_back(e.step);
    id_i_.push_back(e.id_i);
    id_j_.push_back(e.id_j);
    midpoint_.push_back(e.midpoint);
    sigma_vm_.push_back(e.stress.sigma_vm);
    sigma_axial_.push_back(e.stress.sigma_axial);
    tau_.push_back(e.stress.tau);
    tension_.push_back(e.stress.tension);
    bending_.push_back(e.stress.bending);
    shear_.push_back(e.stress.shear);
    torsion_.push_back(e.stress.torsion);
    mode_.push_back(static_cast<std::uint8_t>(e.stress.dominant));
  }
}

void BreakEventWriter::write() {
  const std::size_t rows = time_.size();
  if (rows == 0) return;
  time_column_.append(time_.data(), rows);
  step_column_.append(step_.data(), rows);
  id_i_column_.append(id_i_.data(), rows);
  id_j_column_.append(id_j_.data(), rows);
  midpoint_column_.append(midpoint_.front().data(), rows);
  sigma_vm_column_.append(sigma_vm_.data(), rows);
  sigma_axial_column_.append(sigma_axial_.data(), rows);
  tau_column_.append(tau_.data(), rows);
  tension_column_.append(tension_.data(), rows);
  bending_column_.append(bending_.data(), rows);
  shear_column_.append(shear_.data(), rows);
  torsion_column_.append(torsion_.data(), rows);
  mode_column_.append(mode_.data(), rows);
  for (auto* v : {&time_, &sigma_vm_, &sigma_axial_, &tau_, &tension_, &bending_, &shear_,
                  &torsion_})
    v->clear();
  step_.clear();
  id_i_.clear();
  id_j_.clear();
  midpoint_.clear();
  mode_.clear();
}

}  // namespace shard
