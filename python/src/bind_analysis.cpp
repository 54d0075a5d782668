// shard._shard's analysis functions: fragments of a frame (analyse_fragments: union-find labels in
// canonical order and the fragment table), the mass-weighted size distribution and the per-body
// statistics, each the analysis library's own function over arrays the caller hands in.
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "frame_arrays.hpp"
#include "shard/analysis/body_statistics.hpp"

namespace shard::python {
namespace {

py::dict fragment_columns(const std::vector<analysis::Fragment>& fragments) {
  const std::size_t n = fragments.size();
  std::vector<Index> label(n), smallest_id(n);
  std::vector<std::int64_t> particles(n);
  std::vector<double> mass(n), volume(n), d_eq(n);
  std::vector<Vec3> centre(n), velocity(n), box_min(n), box_max(n);
  std::vector<std::int32_t> body(n);
  std::vector<std::uint8_t> mixed(n);
  for (std::size_t k = 0; k < n; ++k) {
    const analysis::Fragment& f = fragments[k];
    label[k] = f.label;
    particles[k] = static_cast<std::int64_t>(f.particles);
    mass[k] = f.mass;
    volume[k] = f.volume;
    centre[k] = f.centre;
    velocity[k] = f.velocity;
    d_eq[k] = f.d_eq;
    box_min[k] = f.box_min;
    box_max[k] = f.box_max;
    body[k] = f.body;
    mixed[k] = f.mixed_bodies ? 1 : 0;
    smallest_id[k] = f.smallest_id;
  }
  py::dict d;
  d["label"] = to_array(std::move(label));
  d["particles"] = to_array(std::move(particles));
  d["mass"] = to_array(std::move(mass));
  d["volume"] = to_array(std::move(volume));
  d["centre"] = rows_array(centre);
  d["velocity"] = rows_array(velocity);
  d["d_eq"] = to_array(std::move(d_eq));
  d["box_min"] = rows_array(box_min);
  d["box_max"] = rows_array(box_max);
  d["body"] = to_array(std::move(body));
  d["mixed_bodies"] = to_array(std::move(mixed)).attr("astype")("bool");
  d["smallest_id"] = to_array(std::move(smallest_id));
  return d;
}

py::dict fragments(const In<Index>& id, const In<double>& position, const In<double>& velocity,
                   const In<double>& radius, const In<double>& mass, const In<std::int32_t>& body,
                   const In<Index>& bonds) {
  const FrameArrays frame = frame_arrays(id, position, velocity, radius, mass, body, bonds);
  analysis::FragmentAnalysis result = analysis::analyse_fragments(frame.sample(), frame.bonds());
  py::dict d = fragment_columns(result.fragments);
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

py::dict body_columns(const analysis::BodyReport& report) {
  const std::size_t n = report.bodies.size();
  std::vector<std::int32_t> body(n);
  std::vector<std::int64_t> particles(n), fragments(n);
  std::vector<double> mass(n), largest(n), x10(n), x50(n), x90(n);
  std::vector<std::uint8_t> broken(n);
  py::list distributions;
  for (std::size_t k = 0; k < n; ++k) {
    const analysis::BodyStatistics& b = report.bodies[k];
    body[k] = b.body;
    particles[k] = static_cast<std::int64_t>(b.particles);
    fragments[k] = static_cast<std::int64_t>(b.fragments);
    mass[k] = b.mass;
    largest[k] = b.largest_fraction;
    broken[k] = b.broken ? 1 : 0;
    x10[k] = b.fsd.x10;
    x50[k] = b.fsd.x50;
    x90[k] = b.fsd.x90;
    distributions.append(distribution_dict(b.fsd));
  }
  py::dict d;
  d["body"] = to_array(std::move(body));
  d["particles"] = to_array(std::move(particles));
  d["mass"] = to_array(std::move(mass));
  d["fragments"] = to_array(std::move(fragments));
  d["largest_fraction"] = to_array(std::move(largest));
  d["broken"] = to_array(std::move(broken)).attr("astype")("bool");
  d["x10"] = to_array(std::move(x10));
  d["x50"] = to_array(std::move(x50));
  d["x90"] = to_array(std::move(x90));
  d["distributions"] = distributions;
  return d;
}

py::dict body_statistics(const In<Index>& id, const In<double>& position, const In<double>& velocity,
                         const In<double>& radius, const In<double>& mass, const In<std::int32_t>& body,
                         const In<Index>& bonds, double intact_fraction, double fines_size) {
  if (!(intact_fraction > 0 && intact_fraction <= 1))
    throw py::value_error("intact_fraction must lie in (0, 1]: 1 counts a body broken once any piece broke off");
  const FrameArrays frame = frame_arrays(id, position, velocity, radius, mass, body, bonds);
  const auto fragments = analysis::analyse_fragments(frame.sample(), frame.bonds()).fragments;
  const analysis::BodyReport report =
      analysis::body_statistics(frame.sample(), fragments, intact_fraction, fines_size);
  py::dict d = body_columns(report);
  d["broken_count"] = report.broken;
  d["breakage_probability"] = report.breakage_probability;
  d["intact_fraction"] = report.intact_fraction;
  d["pooled"] = distribution_dict(report.pooled);
  return d;
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
