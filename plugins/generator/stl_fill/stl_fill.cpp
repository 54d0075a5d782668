#include "stl_fill.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "shard/geometry/advancing_front.hpp"
#include "shard/geometry/generator_params.hpp"
#include "shard/geometry/mesh_repair.hpp"
#include "shard/geometry/packing_io.hpp"
#include "shard/geometry/packing_quality.hpp"
#include "shard/geometry/stl.hpp"
#include "signed_distance_field.hpp"

namespace shard::stl_fill {

std::vector<ParamSpec> stl_fill_params() {
  using geometry::param;
  const std::monostate required;
  return {
      param("file", ParamType::String, "", "closed STL surface of the body (relative to the scene folder)", required),
      param("scale", ParamType::Number, "1", "factor from STL units to m (0.001 for a file in mm)", 1.0,
            geometry::kPositive),
      param("offset", ParamType::Vector3, "m", "translation applied after scaling", Vec3(Vec3::Zero())),
      param("diameter_min", ParamType::Number, "m", "smallest sphere diameter (uniform PSD)", required,
            geometry::kPositive),
      param("diameter_max", ParamType::Number, "m", "largest sphere diameter (uniform PSD)", required,
            geometry::kPositive),
      param("psd_table", ParamType::String, "",
            "optional CSV 'diameter_m, cumulative_number_fraction'; replaces the uniform PSD", std::string()),
      param("gap", ParamType::Number, "1", "bond pairs whose surface gap < gap x mean radius of the pair",
            kDefaultGap, geometry::kNonNegative),
      param("voxel_size", ParamType::Number, "m", "signed-distance voxel; 0 = diameter_min / 4", 0.0,
            geometry::kNonNegative),
      param("seed_offset", ParamType::Integer, "1", "added to the scene seed for this body", 0.0),
      param("save", ParamType::String, "", "optional CSV path to store the packing for from_file", std::string()),
      param("weld_tolerance", ParamType::Number, "m",
            "vertices closer than this are one vertex; 0 = 1e-6 x bounding-box diagonal (at least 8 float32 ulps)",
            0.0, geometry::kNonNegative),
      param("gap_tolerance", ParamType::Number, "m",
            "cracks up to this wide count as closed; 0 = min(1e-3 x bounding-box diagonal, diameter_min / 2)", 0.0,
            geometry::kNonNegative),
      param("conform_surface", ParamType::Boolean, "",
            "also place spheres tangent to the surface, so plane faces end flat to the grain (where a fixture bears)",
            false),
      param("max_hole_fraction", ParamType::Number, "1",
            "error if more of the body than this stays further than d_max from any sphere", 0.02, {0.0, 1.0}),
  };
}

StlFillSettings stl_fill_settings(const ParamSet& params) {
  StlFillSettings s;
  s.file = params.text("file");
  s.scale = params.number("scale");
  s.offset = params.vec3("offset");
  s.diameter_min = params.number("diameter_min");
  s.diameter_max = params.number("diameter_max");
  s.psd_table = params.text("psd_table");
  s.gap = params.number("gap");
  s.voxel_size = params.number("voxel_size");
  s.seed_offset = params.integer("seed_offset");
  s.save = params.text("save");
  s.max_hole_fraction = params.number("max_hole_fraction");
  s.conform_surface = params.flag("conform_surface");
  s.weld_tolerance = params.number("weld_tolerance");
  s.gap_tolerance = params.number("gap_tolerance");
  return s;
}

GeneratedBody StlFill::generate(const GeneratorContext& context) const {
  const auto start = std::chrono::steady_clock::now();
  const auto log = [&](const std::string& line) {
    if (context.log) context.log("stl_fill: " + line);
  };
  const auto path = geometry::resolve_against(context.scene_dir, settings_.file);
  const geometry::SizeDistribution psd =
      settings_.psd_table.empty()
          ? geometry::SizeDistribution::uniform(settings_.diameter_min, settings_.diameter_max)
          : geometry::SizeDistribution::from_table(geometry::resolve_against(context.scene_dir, settings_.psd_table));
  geometry::TriangleMesh mesh = geometry::read_stl(path, settings_.scale);
  // Welded before the offset: the float32 floor of the weld tolerance belongs to the file's coordinates.
  geometry::SolidTolerances tolerances{settings_.weld_tolerance, settings_.gap_tolerance};
  if (!(tolerances.gap > 0.0)) {
    // A crack narrower than the smallest sphere's radius cannot let a sphere out or change which fit.
    const geometry::Box box = geometry::bounding_box(mesh);
    tolerances.gap = std::min(geometry::kDefaultRelativeGap * (box.upper - box.lower).norm(), 0.5 * psd.d_min());
  }
  const geometry::SolidRepair repair = geometry::repair_closed_solid(mesh, path, tolerances);
  for (Vec3& v : mesh.vertices) v += settings_.offset;
  log(fmt::format("'{}': {}", path.string(), repair.summary()));
  const double voxel = settings_.voxel_size > 0.0 ? settings_.voxel_size : psd.d_min() / 4.0;
  geometry::Box bounds = geometry::bounding_box(mesh);
  const double body_volume = geometry::signed_volume(mesh);
  const double smallest_extent = (bounds.upper - bounds.lower).minCoeff();
  if (smallest_extent < psd.d_max())
    throw geometry::FillError(fmt::format("STL body '{}' is too thin for the particle size: its smallest extent "
                                          "{:.4g} m is below diameter_max = {:.4g} m. Reduce the diameters or check "
                                          "'scale' (0.001 for a file in mm)",
                                          path.string(), smallest_extent, psd.d_max()));
  // A band of r_max plus a few voxels keeps "SDF <= -r" exact for every candidate sphere. Placing
  // spheres against the surface also needs the normal where a worked sphere of radius r_max, with a
  // sphere of diameter d_max between it and the surface, sits: 1.5 d_max deep.
  const double band = (settings_.conform_surface ? 1.5 : 0.5) * psd.d_max() + 3.0 * voxel;
  const SignedDistanceField field(
      mesh, voxel, band,
      repair.edges.open_edges == 0 ? geometry::SignRule::RayMajority : geometry::SignRule::WindingWhenRaysDisagree);
  const geometry::SignedDistance distance = [&field](const Vec3& p) { return field.distance(p); };
  const auto seconds_since_start = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  log(fmt::format("'{}': {} faces, volume {:.6g} m^3, voxel {:.4g} m, {} active voxels ({:.2f} s)", path.string(),
                  mesh.faces.size(), body_volume, voxel, field.active_voxels(), seconds_since_start()));

  geometry::FrontFillOptions options;
  options.seed = context.seed + static_cast<std::uint64_t>(settings_.seed_offset);
  options.conform_to_surface = settings_.conform_surface;
  options.normal_step = voxel;
  geometry::SpherePacking packing;
  try {
    packing = geometry::advancing_front_fill(distance, bounds, psd, options);
  } catch (const geometry::FillError& e) {
    throw geometry::FillError(fmt::format("STL body '{}': {}", path.string(), e.what()));
  }
  log(fmt::format("{} spheres placed ({:.2f} s)", packing.centre.size(), seconds_since_start()));
  geometry::BondList bonds = geometry::bond_by_gap(packing, settings_.gap);
  const double seconds = seconds_since_start();

  geometry::QualityInputs inputs;
  inputs.body_volume = body_volume;
  inputs.target = &psd;
  inputs.distance = &distance;
  inputs.bounds = bounds;
  inputs.seconds = seconds;
  auto quality = geometry::packing_quality(packing, bonds, inputs);
  log(geometry::format_quality(quality));
  for (const auto& [name, value] : quality)
    if (name == "hole_fraction" && value > settings_.max_hole_fraction)
      throw geometry::FillError(fmt::format(
          "STL body '{}' was filled only partly: {:.1f}% of its volume lies further than d_max from any sphere "
          "(limit max_hole_fraction = {:.1f}%). The body has parts the front cannot reach from the seed: "
          "separate pieces in one STL, or necks thinner than d_max = {:.4g} m. Split the STL or reduce the "
          "diameters",
          path.string(), 100.0 * value, 100.0 * settings_.max_hole_fraction, psd.d_max()));
  if (!settings_.save.empty()) {
    const auto out = geometry::resolve_against(context.scene_dir, settings_.save);
    geometry::save_packing_csv(out, packing, bonds,
                               {fmt::format("stl_fill file={} scale={} d={}..{} gap={} seed={} conform_surface={}",
                                            settings_.file, settings_.scale, psd.d_min(), psd.d_max(), settings_.gap,
                                            options.seed, settings_.conform_surface),
                                geometry::format_quality(quality)});
    log(fmt::format("packing saved to '{}' and '{}'", out.string(), geometry::bonds_path_for(out).string()));
  }
  return geometry::to_generated_body(std::move(packing), std::move(bonds), {}, std::move(quality));
}

}  // namespace shard::stl_fill
