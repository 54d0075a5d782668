// shard._shard.RunFile: the kernel's reader of run.h5 (shard/run_file.hpp), the one place that
// knows the layout. Frames, series, walls, break events and body impacts come back as dicts of
// numpy arrays, one entry per dataset of docs/reference/output-format.md.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>

#include "arrays.hpp"
#include "bindings.hpp"
#include "frame_arrays.hpp"
#include "shard/analysis/plate_outcome.hpp"
#include "shard/run_file.hpp"

namespace shard::python {
namespace {

py::dict metadata_dict(const RunMetadata& meta) {
  py::dict d;
  d["scene"] = meta.scene_text;
  d["scene_file"] = meta.scene_file;
  d["seed"] = meta.seed;
  d["shard_version"] = meta.shard_version;
  d["git_revision"] = meta.git_revision;
  py::dict plugins, quality, notes;
  for (const auto& [name, text] : meta.plugins) plugins[py::str(name)] = text;
  for (const auto& [name, value] : meta.generator_quality) quality[py::str(name)] = value;
  for (const auto& [name, text] : meta.notes) notes[py::str(name)] = text;
  d["plugins"] = plugins;
  d["generator_quality"] = quality;
  d["notes"] = notes;
  return d;
}

// Surviving bonds as an (m, 2) int32 array of row indices, the layout's own shape.
py::array_t<Index> bond_rows(const std::vector<Index>& i, const std::vector<Index>& j) {
  py::array_t<Index> out({static_cast<py::ssize_t>(i.size()), py::ssize_t{2}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t r = 0; r < i.size(); ++r) {
    view(static_cast<py::ssize_t>(r), 0) = i[r];
    view(static_cast<py::ssize_t>(r), 1) = j[r];
  }
  return out;
}

py::dict frame_dict(FrameData&& f) {
  py::dict d;
  d["step"] = f.step;
  d["time"] = f.time;
  d["id"] = to_array(std::move(f.id));
  d["position"] = rows_array(f.position);
  d["velocity"] = rows_array(f.velocity);
  d["omega"] = rows_array(f.omega);
  d["radius"] = to_array(std::move(f.radius));
  d["mass"] = to_array(std::move(f.mass));
  d["mass_source"] = f.mass_source;
  d["material"] = to_array(std::move(f.material));
  d["body"] = to_array(std::move(f.body));
  d["bonds"] = bond_rows(f.bond_i, f.bond_j);
  d["fragment"] = f.fragment ? py::object(to_array(std::move(*f.fragment))) : py::object(py::none());
  return d;
}

py::dict break_events_dict(const std::vector<BondBreakEvent>& events) {
  const std::size_t n = events.size();
  std::vector<double> time(n), sigma_vm(n), sigma_axial(n), tau(n), tension(n), bending(n), shear(n), torsion(n);
  std::vector<std::int64_t> step(n);
  std::vector<Index> id_i(n), id_j(n);
  std::vector<Vec3> midpoint(n);
  std::vector<std::uint8_t> mode(n);
  for (std::size_t k = 0; k < n; ++k) {
    const BondBreakEvent& e = events[k];
    time[k] = e.time;
    step[k] = e.step;
    id_i[k] = e.id_i;
    id_j[k] = e.id_j;
    midpoint[k] = e.midpoint;
    sigma_vm[k] = e.stress.sigma_vm;
    sigma_axial[k] = e.stress.sigma_axial;
    tau[k] = e.stress.tau;
    tension[k] = e.stress.tension;
    bending[k] = e.stress.bending;
    shear[k] = e.stress.shear;
    torsion[k] = e.stress.torsion;
    mode[k] = static_cast<std::uint8_t>(e.stress.dominant);
  }
  py::dict d;
  d["time"] = to_array(std::move(time));
  d["step"] = to_array(std::move(step));
  d["id_i"] = to_array(std::move(id_i));
  d["id_j"] = to_array(std::move(id_j));
  d["midpoint"] = rows_array(midpoint);
  d["sigma_vm"] = to_array(std::move(sigma_vm));
  d["sigma_axial"] = to_array(std::move(sigma_axial));
  d["tau"] = to_array(std::move(tau));
  d["tension"] = to_array(std::move(tension));
  d["bending"] = to_array(std::move(bending));
  d["shear"] = to_array(std::move(shear));
  d["torsion"] = to_array(std::move(torsion));
  d["mode"] = to_array(std::move(mode));
  return d;
}

py::dict body_impacts_dict(const std::vector<BodyImpact>& impacts) {
  const std::size_t n = impacts.size();
  std::vector<std::uint8_t> hit(n);
  std::vector<std::int64_t> step(n);
  std::vector<double> time(n), speed(n), angle(n);
  std::vector<Vec3> velocity(n), normal(n);
  std::vector<std::int32_t> wall(n);
  for (std::size_t b = 0; b < n; ++b) {
    const BodyImpact& i = impacts[b];
    hit[b] = i.hit ? 1 : 0;
    step[b] = i.step;
    time[b] = i.time;
    velocity[b] = i.velocity;
    normal[b] = i.normal;
    wall[b] = i.wall;
    speed[b] = i.speed();
    angle[b] = i.angle_degrees();
  }
  py::dict d;
  d["hit"] = to_array(std::move(hit)).attr("astype")("bool");
  d["step"] = to_array(std::move(step));
  d["time"] = to_array(std::move(time));
  d["velocity"] = rows_array(velocity);
  d["normal"] = rows_array(normal);
  d["wall"] = to_array(std::move(wall));
  d["speed"] = to_array(std::move(speed));
  d["angle"] = to_array(std::move(angle));
  return d;
}

}  // namespace

void bind_run_file(py::module_& m) {
  py::class_<RunFile>(m, "RunFile", "The reader of one run file (run.h5)")
      .def(py::init([](const std::filesystem::path& path) { return RunFile(path); }), py::arg("path"))
      .def_property_readonly("path", &RunFile::path)
      .def("metadata", [](const RunFile& f) { return metadata_dict(f.metadata()); })
      .def_property_readonly("abi_version", &RunFile::abi_version)
      .def("frames", &RunFile::frames, "The numbers of the complete frames, ascending")
      .def(
          "read_frame",
          [](const RunFile& f, std::size_t k, std::optional<double> density) {
            return frame_dict(f.read_frame(k, density));
          },
          py::arg("k"), py::arg("density") = py::none())
      .def_property_readonly("series_rows", &RunFile::series_rows)
      .def("read_series", [](const RunFile& f, const std::string& name) { return to_array(f.read_series(name)); })
      .def("read_integer_series",
           [](const RunFile& f, const std::string& name) { return to_array(f.read_integer_series(name)); })
      .def("wall_names", &RunFile::wall_names)
      .def("read_wall_series",
           [](const RunFile& f, const std::string& wall, const std::string& quantity) {
             return rows_array(f.read_wall_series(wall, quantity));
           })
      .def("read_wall_impact_energy",
           [](const RunFile& f, const std::string& wall) { return to_array(f.read_wall_impact_energy(wall)); })
      .def("read_wall_impacts",
           [](const RunFile& f, const std::string& wall) { return to_array(f.read_wall_impacts(wall)); })
      .def("read_break_events", [](const RunFile& f) { return break_events_dict(f.read_break_events()); })
      .def("read_body_impacts", [](const RunFile& f) { return body_impacts_dict(f.read_body_impacts()); })
      .def(
          "body_statistics",
          [](const RunFile& f, std::size_t k, double intact_fraction, double fines_size,
             std::optional<double> density) {
            // The frame's bodies with each one's first wall contact, as `shard fragments --by-body`.
            const analysis::RunBodies bodies = analysis::analyse_run_bodies(
                f, static_cast<std::int64_t>(k), intact_fraction, fines_size, density);
            return body_report_dict(bodies.report);
          },
          py::arg("k"), py::arg("intact_fraction"), py::arg("fines_size"), py::arg("density") = py::none());
}

}  // namespace shard::python
