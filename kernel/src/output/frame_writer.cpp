#include "frame_writer.hpp"

#include <string>

#include "h5_io.hpp"
#include "shard/output.hpp"

namespace shard {

namespace {

const double* flat(const std::vector<Vec3>& v) { return v.empty() ? nullptr : v.front().data(); }

void require_size(std::size_t actual, std::size_t n, const char* what) {
  if (actual != n)
    throw OutputError(std::string("frame not written: ") + what + " has " +
                      std::to_string(actual) + " entries for " + std::to_string(n) +
                      " particles");
}

}  // namespace

void collect_frame_bonds(const Particles& particles, const Bonds& bonds,
                         const std::vector<Index>* fragment_labels, std::vector<Index>& pairs) {
  const std::size_t n = particles.size();
  require_size(particles.id.size(), n, "id");
  require_size(particles.velocity.size(), n, "velocity");
  require_size(particles.omega.size(), n, "omega");
  require_size(particles.radius.size(), n, "radius");
  require_size(particles.material.size(), n, "material");
  require_size(particles.body.size(), n, "body");
  if (fragment_labels != nullptr) require_size(fragment_labels->size(), n, "fragment labels");

  // Bonds flagged broken but not yet removed are not part of the snapshot.
  const bool flags = bonds.broken.size() == bonds.size();
  pairs.clear();
  for (std::size_t k = 0; k < bonds.size(); ++k) {
    if (flags && bonds.broken[k] != 0) continue;
    const Index i = bonds.i[k], j = bonds.j[k];
    if (i < 0 || j < 0 || static_cast<std::size_t>(i) >= n || static_cast<std::size_t>(j) >= n)
      throw OutputError("frame not written: bond " + std::to_string(k) + " joins particles " +
                        std::to_string(i) + " and " + std::to_string(j) + " of " +
                        std::to_string(n));
    pairs.push_back(i);
    pairs.push_back(j);
  }
}

void write_frame_datasets(hid_t group, const Particles& particles, const std::vector<Index>& pairs,
                          const std::vector<Index>* fragment_labels) {
  const std::size_t n = particles.size();
  h5::write_dataset(group, "id", particles.id.data(), n);
  h5::write_dataset(group, "position", flat(particles.position), n, 3);
  h5::write_dataset(group, "velocity", flat(particles.velocity), n, 3);
  h5::write_dataset(group, "omega", flat(particles.omega), n, 3);
  h5::write_dataset(group, "radius", particles.radius.data(), n);
  // Masses are stored so that fragment masses need no density from the user.
  h5::write_dataset(group, "mass", particles.mass.data(), n);
  h5::write_dataset(group, "material", particles.material.data(), n);
  h5::write_dataset(group, "body", particles.body.data(), n);
  h5::write_dataset(group, "bonds", pairs.data(), pairs.size() / 2, 2);
  if (fragment_labels != nullptr) h5::write_dataset(group, "fragment", fragment_labels->data(), n);
}

void write_frame_part_datasets(hid_t group, const FramePart& part) {
  const Particles& p = *part.particles;
  const std::size_t n = p.id.size();
  require_size(p.position.size(), n, "position");
  require_size(p.velocity.size(), n, "velocity");
  require_size(p.omega.size(), n, "omega");
  require_size(p.radius.size(), n, "radius");
  require_size(p.mass.size(), n, "mass");
  require_size(p.material.size(), n, "material");
  require_size(p.body.size(), n, "body");
  if (part.labelled) require_size(part.fragment_labels ? part.fragment_labels->size() : 0, n, "fragment labels");
  const std::size_t bonds = part.bond_rows ? part.bond_rows->size() / 2 : 0;
  h5::Handle transfer = h5::plist_handle(H5Pcreate(H5P_DATASET_XFER), "creating a transfer list");
  if (part.configure_transfer) part.configure_transfer(transfer.get());
  const hid_t x = transfer.get();
  const std::size_t first = part.first_row, total = part.total_rows;
  h5::write_dataset_part(group, "id", p.id.data(), first, n, total, 0, x);
  h5::write_dataset_part(group, "position", flat(p.position), first, n, total, 3, x);
  h5::write_dataset_part(group, "velocity", flat(p.velocity), first, n, total, 3, x);
  h5::write_dataset_part(group, "omega", flat(p.omega), first, n, total, 3, x);
  h5::write_dataset_part(group, "radius", p.radius.data(), first, n, total, 0, x);
  h5::write_dataset_part(group, "mass", p.mass.data(), first, n, total, 0, x);
  h5::write_dataset_part(group, "material", p.material.data(), first, n, total, 0, x);
  h5::write_dataset_part(group, "body", p.body.data(), first, n, total, 0, x);
  h5::write_dataset_part(group, "bonds", bonds ? part.bond_rows->data() : nullptr, part.first_bond, bonds,
                         part.total_bonds, 2, x);
  if (part.labelled)
    h5::write_dataset_part(group, "fragment", part.fragment_labels->data(), first, n, total, 0, x);
}

}  // namespace shard
