// shard._shard's analysis functions: fragments of a frame (analyse_fragments: union-find labels in
// canonical order and the fragment table), the mass-weighted size distribution and the per-body
// statistics, each the analysis library's own function over arrays the caller hands in.
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "frame_arrays.hpp"
#include "run_table.hpp"
#include "shard/analysis/body_statistics.hpp"
#include "shard/analysis/run_tables.hpp"

namespace shard::python {
namespace {

py::dict fragments(const In<Index>& id, const In<double>& position, const In<double>& velocity,
                   const In<double>& radius, const In<double>& mass, const In<std::int32_t>& body,
                   const In<Index>& bonds) {
  const FrameArrays frame = frame_arrays(id, position, velocity, radius, mass, body, bonds);
  analysis::FragmentAnalysis result = analysis::analyse_fragments(frame.sample(), frame.bonds());
  const analysis::SizeDistribution fsd = analysis::size_distribution(result.fragments);
  py::dict d = table_dict(analysis::fragment_run_table(result.fragments, fsd));
  d["labels"] = to_array(std::move(result.labels));
  return d;
}

py::dict size_distribution(const In<double>& d, const In<double>& mass, double fines_size) {
  const std::vector<double> sizes = to_vector(d, "d"), masses = to_vector(mass, "mass");
  if (sizes.size() != masses.size()) throw py::value_error("d and mass must have the same length");
  return distribution_dict(analysis::size_distribution(sizes, masses, fines_size));
}

double characteristic_size(const In<double>& d, const In<double>& cumulative, double p) {
  const std::vector<double> sizes = to_vector(d, "d"), q = to_vector(cumulative, "cumulative");
  if (sizes.size() != q.size() || sizes.empty())
    throw py::value_error("d and cumulative must be of one length, at least 1");
  if (!(p > 0 && p <= 1)) throw py::value_error("p must lie in (0, 1]: 0.5 gives x50");
  std::vector<analysis::DistributionPoint> points(sizes.size());
  for (std::size_t k = 0; k < points.size(); ++k) points[k] = {sizes[k], q[k]};
  return analysis::characteristic_size(points, p);
}

py::dict body_statistics(const In<Index>& id, const In<double>& position, const In<double>& velocity,
                         const In<double>& radius, const In<double>& mass, const In<std::int32_t>& body,
                         const In<Index>& bonds, double intact_fraction, double fines_size) {
  if (!(intact_fraction > 0 && intact_fraction <= 1))
    throw py::value_error("intact_fraction must lie in (0, 1]: 1 counts a body broken once any piece broke off");
  const FrameArrays frame = frame_arrays(id, position, velocity, radius, mass, body, bonds);
  const auto fragments = analysis::analyse_fragments(frame.sample(), frame.bonds()).fragments;
  return body_report_dict(analysis::body_statistics(frame.sample(), fragments, intact_fraction, fines_size));
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def("fragments", &fragments, py::arg("id"), py::arg("position"), py::arg("velocity"), py::arg("radius"),
        py::arg("mass"), py::arg("body"), py::arg("bonds"),
        "Fragments of a frame: canonical labels (0 the heaviest) and one table row per fragment");
  m.def("size_distribution", &size_distribution, py::arg("d"), py::arg("mass"), py::arg("fines_size") = 0.0,
        "Mass-weighted cumulative size distribution Q(d) with x10, x50, x90");
  m.def("characteristic_size", &characteristic_size, py::arg("d"), py::arg("cumulative"), py::arg("p"),
        "x_p of a distribution's points (p in (0, 1])");
  m.def("body_statistics", &body_statistics, py::arg("id"), py::arg("position"), py::arg("velocity"),
        py::arg("radius"), py::arg("mass"), py::arg("body"), py::arg("bonds"), py::arg("intact_fraction"),
        py::arg("fines_size") = 0.0, "Per parent body: fragments, largest fraction, broken, size distribution");
}

}  // namespace shard::python
