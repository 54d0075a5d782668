#include "frame_arrays.hpp"

#include <stdexcept>

#include "run_table.hpp"
#include "shard/analysis/run_tables.hpp"

namespace shard::python {

FrameArrays frame_arrays(const In<Index>& id, const In<double>& position, const In<double>& velocity,
                         const In<double>& radius, const In<double>& mass, const In<std::int32_t>& body,
                         const In<Index>& bonds) {
  FrameArrays f{to_vector(id, "id"),     to_rows(position, "position"), to_rows(velocity, "velocity"),
                to_vector(radius, "radius"), to_vector(mass, "mass"),     to_vector(body, "body"),
                {},
                {}};
  if (bonds.ndim() != 2 || bonds.shape(1) != 2)
    throw py::value_error("bonds must be an (m, 2) array of particle row indices");
  auto rows = bonds.unchecked<2>();
  for (py::ssize_t r = 0; r < bonds.shape(0); ++r) {
    f.bond_i.push_back(rows(r, 0));
    f.bond_j.push_back(rows(r, 1));
  }
  try {
    analysis::check_sample(f.sample());
    analysis::check_bonds(f.id.size(), f.bonds());
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  return f;
}

py::dict distribution_dict(const analysis::SizeDistribution& fsd) {
  std::vector<double> d, cumulative;
  for (const auto& point : fsd.points) {
    d.push_back(point.d);
    cumulative.push_back(point.cumulative);
  }
  py::dict out;
  out["d"] = to_array(std::move(d));
  out["cumulative"] = to_array(std::move(cumulative));
  out["fragments"] = fsd.fragments;
  out["total_mass"] = fsd.total_mass;
  out["x10"] = fsd.x10;
  out["x50"] = fsd.x50;
  out["x90"] = fsd.x90;
  out["fines_size"] = fsd.fines_size;
  out["fines_mass"] = fsd.fines_mass;
  return out;
}

py::dict body_report_dict(const analysis::BodyReport& report) {
  py::dict d = table_dict(analysis::body_run_table(report));
  py::list distributions;
  for (const auto& body : report.bodies) distributions.append(distribution_dict(body.fsd));
  d["distributions"] = distributions;
  d["pooled"] = distribution_dict(report.pooled);
  return d;
}

}  // namespace shard::python
