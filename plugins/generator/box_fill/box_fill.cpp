#include "box_fill.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "shard/geometry/advancing_front.hpp"
#include "shard/geometry/generator_params.hpp"
#include "shard/geometry/packing_io.hpp"
#include "shard/geometry/packing_quality.hpp"
#include "shard/geometry/random.hpp"

namespace shard::box_fill {
namespace {

// Lattice sites of spacing d (nearest-neighbour distance) whose sphere of diameter d fits in the box.
std::vector<Vec3> lattice_sites(Lattice lattice, const Vec3& lo, const Vec3& hi, double d) {
  const Vec3 inner_lo = lo + Vec3::Constant(0.5 * d);
  const Vec3 inner_hi = hi - Vec3::Constant(0.5 * d);
  std::vector<Vec3> sites;
  const auto keep = [&](const Vec3& p) {
    // A relative slack so sites exactly on the inner box survive rounding.
    const double slack = 1e-12 * d;
    if ((p.array() >= inner_lo.array() - slack).all() && (p.array() <= inner_hi.array() + slack).all()) sites.push_back(p);
  };
  const Vec3 extent = inner_hi - inner_lo;
  if (lattice == Lattice::Cubic) {
    for (int k = 0; k * d <= extent.z() + 1e-12 * d; ++k)
      for (int j = 0; j * d <= extent.y() + 1e-12 * d; ++j)
        for (int i = 0; i * d <= extent.x() + 1e-12 * d; ++i)
          keep(inner_lo + d * Vec3(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)));
  } else if (lattice == Lattice::Fcc) {
    const double a = d * std::sqrt(2.0);  // cube edge of the conventional cell
    const Vec3 basis[4] = {{0, 0, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}, {0.5, 0.5, 0}};
    for (int k = 0; k * a <= extent.z() + 1e-12 * d; ++k)
      for (int j = 0; j * a <= extent.y() + 1e-12 * d; ++j)
        for (int i = 0; i * a <= extent.x() + 1e-12 * d; ++i)
          for (const Vec3& b : basis)
            keep(inner_lo + a * (Vec3(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)) + b));
  } else {  // hcp: triangular layers stacked ABAB
    const double row = d * std::sqrt(3.0) / 2.0;
    const double layer = d * std::sqrt(2.0 / 3.0);
    for (int k = 0; k * layer <= extent.z() + 1e-12 * d; ++k) {
      const Vec3 shift = (k % 2 == 0) ? Vec3::Zero() : Vec3(0.5 * d, d * std::sqrt(3.0) / 6.0, 0.0);
      for (int j = 0; j * row <= extent.y() + 1e-12 * d; ++j)
        for (int i = 0; i * d <= extent.x() + 1e-12 * d; ++i)
          keep(inner_lo + shift + Vec3(d * (static_cast<double>(i) + 0.5 * static_cast<double>(j % 2)),
                                       row * static_cast<double>(j), layer * static_cast<double>(k)));
    }
  }
  return sites;
}

}  // namespace

Lattice parse_lattice(const std::string& name) {
  if (name == "cubic") return Lattice::Cubic;
  if (name == "hcp") return Lattice::Hcp;
  if (name == "fcc") return Lattice::Fcc;
  if (name == "random") return Lattice::Random;
  throw std::invalid_argument(fmt::format("box_fill: lattice '{}' is unknown; use \"fcc\", \"hcp\", \"cubic\" or \"random\"", name));
}

std::vector<ParamSpec> box_fill_params() {
  using geometry::param;
  const std::monostate required;
  return {
      param("min_corner", ParamType::Vector3, "m", "lower corner of the box", required),
      param("max_corner", ParamType::Vector3, "m", "upper corner of the box", required),
      param("lattice", ParamType::String, "", "\"fcc\", \"hcp\", \"cubic\" (spacing diameter_max) or \"random\"",
            std::string("random")),
      param("diameter_min", ParamType::Number, "m", "smallest diameter (uniform in diameter)", required, geometry::kPositive),
      param("diameter_max", ParamType::Number, "m", "largest diameter; lattice spacing", required, geometry::kPositive),
      param("gap", ParamType::Number, "1", "bond pairs whose surface gap < gap x mean radius of the pair", 0.7,
            geometry::kNonNegative),
      param("conform_surface", ParamType::Boolean, "",
            "random lattice: also place spheres tangent to the faces, so they end flat to the grain", false),
      param("bond", ParamType::Boolean, "", "bond neighbours closer than the gap", true),
      param("seed_offset", ParamType::Integer, "1", "added to the scene seed for this body", 0.0),
  };
}

BoxFillSettings box_fill_settings(const ParamSet& params) {
  BoxFillSettings s;
  s.min_corner = params.vec3("min_corner");
  s.max_corner = params.vec3("max_corner");
  s.lattice = parse_lattice(params.text("lattice"));
  s.diameter_min = params.number("diameter_min");
  s.diameter_max = params.number("diameter_max");
  s.gap = params.number("gap");
  s.bond = params.flag("bond");
  s.conform_surface = params.flag("conform_surface");
  s.seed_offset = params.integer("seed_offset");
  return s;
}

BoxFill::BoxFill(BoxFillSettings settings) : settings_(std::move(settings)) {
  const Vec3 extent = settings_.max_corner - settings_.min_corner;
  if (!(settings_.diameter_min > 0.0) || !(settings_.diameter_max >= settings_.diameter_min))
    throw std::invalid_argument(fmt::format("box_fill: need 0 < diameter_min <= diameter_max, got {} and {}",
                                            settings_.diameter_min, settings_.diameter_max));
  if (!(extent.minCoeff() >= settings_.diameter_max))
    throw std::invalid_argument(fmt::format("box_fill: the box ({:.4g} x {:.4g} x {:.4g} m) must be at least "
                                            "diameter_max = {:.4g} m wide along every axis, with max_corner > min_corner",
                                            extent.x(), extent.y(), extent.z(), settings_.diameter_max));
  if (settings_.conform_surface && settings_.lattice != Lattice::Random)
    throw std::invalid_argument(
        "box_fill: conform_surface = true applies to lattice = \"random\"; a lattice's faces are flat already. "
        "Remove conform_surface or use the random lattice");
}

GeneratedBody BoxFill::generate(const GeneratorContext& context) const {
  const auto start = std::chrono::steady_clock::now();
  const geometry::Box box{settings_.min_corner, settings_.max_corner};
  const auto psd = geometry::SizeDistribution::uniform(settings_.diameter_min, settings_.diameter_max);
  const std::uint64_t seed = context.seed + static_cast<std::uint64_t>(settings_.seed_offset);
  // Exact inside the box (distance to the nearest face, negative), a lower bound outside.
  const geometry::SignedDistance distance = [&box](const Vec3& p) {
    return std::max((box.lower - p).maxCoeff(), (p - box.upper).maxCoeff());
  };
  geometry::SpherePacking packing;
  if (settings_.lattice == Lattice::Random) {
    geometry::FrontFillOptions options;
    options.seed = seed;
    options.conform_to_surface = settings_.conform_surface;
    packing = geometry::advancing_front_fill(distance, box, psd, options);
  } else {
    packing.centre = lattice_sites(settings_.lattice, box.lower, box.upper, settings_.diameter_max);
    geometry::Random random(seed);
    packing.radius.reserve(packing.centre.size());
    for (std::size_t i = 0; i < packing.centre.size(); ++i)
      packing.radius.push_back(0.5 * psd.diameter_at(random.uniform()));
  }
  geometry::BondList bonds = settings_.bond ? geometry::bond_by_gap(packing, settings_.gap) : geometry::BondList{};
  geometry::QualityInputs inputs;
  inputs.body_volume = (box.upper - box.lower).prod();
  inputs.target = &psd;
  inputs.distance = &distance;
  inputs.bounds = box;
  inputs.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto quality = geometry::packing_quality(packing, bonds, inputs);
  if (context.log) context.log("box_fill: " + geometry::format_quality(quality));
  return geometry::to_generated_body(std::move(packing), std::move(bonds), {}, std::move(quality));
}

}  // namespace shard::box_fill
