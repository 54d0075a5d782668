#include "from_file.hpp"

#include <fmt/core.h>

#include <chrono>
#include <stdexcept>

#include "shard/geometry/generator_params.hpp"
#include "shard/geometry/packing_io.hpp"
#include "shard/geometry/packing_quality.hpp"
#include "shard/geometry/mesh_repair.hpp"
#include "shard/geometry/stl.hpp"
#include "run_frame.hpp"

namespace shard::from_file {

std::vector<ParamSpec> from_file_params() {
  using geometry::param;
  return {
      param("spheres", ParamType::String, "", "CSV x,y,z,r[,material] in m, one sphere per line (or give run)",
            std::string()),
      param("run", ParamType::String, "", "Shard run.h5 whose frame gives spheres and bonds (or give spheres)",
            std::string()),
      param("frame", ParamType::Integer, "1", "frame of run; negative counts from the end (-1 = last)", -1.0),
      param("bonds", ParamType::String, "",
            "CSV i,j (0-based rows); \"auto\" = <spheres>.bonds.csv if present, \"\" = no bonds", std::string("auto")),
      param("body", ParamType::String, "", "optional closed STL of the body, for the solid fraction", std::string()),
      param("scale", ParamType::Number, "1", "STL units to m (0.001 for mm)", 1.0, geometry::kPositive),
      param("max_overlap", ParamType::Number, "1", "refuse overlaps above this fraction of the smaller radius", 0.01,
            geometry::kNonNegative),
  };
}

FromFileSettings from_file_settings(const ParamSet& params) {
  FromFileSettings s;
  s.spheres = params.text("spheres");
  s.run = params.text("run");
  s.frame = params.integer("frame");
  s.bonds = params.text("bonds");
  s.body = params.text("body");
  s.scale = params.number("scale");
  s.max_overlap = params.number("max_overlap");
  return s;
}

namespace {

struct LoadedPacking {
  geometry::StoredPacking stored;
  std::string source;  // for the log line and the errors
};

LoadedPacking load_csv(const FromFileSettings& settings, const std::string& scene_dir) {
  LoadedPacking out;
  const auto spheres_path = geometry::resolve_against(scene_dir, settings.spheres);
  out.stored = geometry::read_spheres_csv(spheres_path);
  std::filesystem::path bonds_path;
  if (settings.bonds == "auto") {
    if (std::filesystem::exists(geometry::bonds_path_for(spheres_path))) bonds_path = geometry::bonds_path_for(spheres_path);
  } else if (!settings.bonds.empty()) {
    bonds_path = geometry::resolve_against(scene_dir, settings.bonds);
  }
  if (!bonds_path.empty()) out.stored.bonds = geometry::read_bonds_csv(bonds_path, out.stored.spheres.centre.size());
  out.source = fmt::format("spheres file '{}'{}", spheres_path.string(),
                           bonds_path.empty() ? std::string(" (no bonds)") : " + '" + bonds_path.string() + "'");
  return out;
}

LoadedPacking load_run_frame(const FromFileSettings& settings, const std::string& scene_dir) {
  const auto run_path = geometry::resolve_against(scene_dir, settings.run);
  RunFrame frame = read_run_frame(run_path, settings.frame);
  LoadedPacking out;
  out.stored.spheres = {std::move(frame.position), std::move(frame.radius)};
  out.stored.material = std::move(frame.material);
  out.stored.bonds = std::move(frame.bonds);
  out.source = fmt::format("run file '{}' frame {} of {} (step {}, t = {:.6g} s)", run_path.string(), frame.index,
                           frame.frame_count, frame.step, frame.time);
  return out;
}

}  // namespace

GeneratedBody FromFile::generate(const GeneratorContext& context) const {
  const auto start = std::chrono::steady_clock::now();
  if (settings_.spheres.empty() == settings_.run.empty())
    throw std::runtime_error("from_file: give exactly one of 'spheres' (CSV) and 'run' (Shard run.h5)");
  LoadedPacking loaded = settings_.run.empty() ? load_csv(settings_, context.scene_dir)
                                               : load_run_frame(settings_, context.scene_dir);
  geometry::StoredPacking& stored = loaded.stored;

  geometry::QualityInputs inputs;
  if (!settings_.body.empty()) {
    const auto body_path = geometry::resolve_against(context.scene_dir, settings_.body);
    auto mesh = geometry::read_stl(body_path, settings_.scale);
    geometry::repair_closed_solid(mesh, body_path);  // welds and accepts what stl_fill accepts
    inputs.body_volume = geometry::signed_volume(mesh);
  }
  inputs.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto quality = geometry::packing_quality(stored.spheres, stored.bonds, inputs);
  for (const auto& [name, value] : quality)
    if (name == "max_overlap" && value > settings_.max_overlap)
      throw std::runtime_error(fmt::format("{}: two spheres overlap by {:.3g} of the smaller radius "
                                           "(limit max_overlap = {:.3g}); the packing is not a valid initial state",
                                           loaded.source, value, settings_.max_overlap));
  if (context.log) context.log(fmt::format("from_file: {}: {}", loaded.source, geometry::format_quality(quality)));
  return geometry::to_generated_body(std::move(stored.spheres), std::move(stored.bonds), std::move(stored.material),
                                     std::move(quality));
}

}  // namespace shard::from_file
