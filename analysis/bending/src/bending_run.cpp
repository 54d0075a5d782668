#include "shard/bending/bending_run.hpp"
#include "shard/analysis/quasi_static.hpp"
#include "shard/bending/test_setup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <span>
#include <stdexcept>
#include <toml++/toml.h>

#include "shard/analysis/fragment_table.hpp"
#include "shard/run_file.hpp"

namespace shard::bending {
namespace {

struct CylinderWall {
  std::string name;
  Vec3 point = Vec3::Zero();
};

Vec3 toml_vec3(const toml::node* n, const Vec3& fallback) {
  const auto* a = n ? n->as_array() : nullptr;
  if (!a || a->size() != 3) return fallback;
  Vec3 v;
  for (std::size_t k = 0; k < 3; ++k) v[static_cast<Eigen::Index>(k)] = (*a)[k].value<double>().value_or(0.0);
  return v;
}

// "name=value; name=value" from the run's plugin record.
std::map<std::string, std::string> plugin_values(const std::string& record) {
  std::map<std::string, std::string> out;
  std::size_t pos = 0;
  while (pos < record.size()) {
    auto end = record.find("; ", pos);
    if (end == std::string::npos) end = record.size();
    const std::string item = record.substr(pos, end - pos);
    if (const auto eq = item.find('='); eq != std::string::npos) out[item.substr(0, eq)] = item.substr(eq + 1);
    pos = end + 2;
  }
  return out;
}

BeamBondParameters bond_parameters(const RunMetadata& meta) {
  BeamBondParameters p;
  for (const auto& [kind, record] : meta.plugins) {
    if (kind != "bond/beam_bond") continue;
    const auto v = plugin_values(record);
    auto number = [&](const char* key, double& target) {
      if (auto it = v.find(key); it != v.end()) target = std::stod(it->second);
    };
    number("youngs_modulus", p.youngs_modulus);
    number("shear_modulus", p.shear_modulus);
    number("poisson_ratio", p.poisson_ratio);
    number("shear_coefficient", p.shear_coefficient);
    number("radius_ratio", p.radius_ratio);
    number("critical_stress", p.critical_stress);
    if (auto it = v.find("breakage"); it != v.end()) p.breakage = it->second == "true";
  }
  return p;
}

double interpolate(const std::vector<double>& t, const std::vector<double>& y, double at) {
  if (t.empty()) return 0;
  const auto it = std::lower_bound(t.begin(), t.end(), at);
  if (it == t.begin()) return y.front();
  if (it == t.end()) return y.back();
  const auto k = static_cast<std::size_t>(it - t.begin());
  const double f = (at - t[k - 1]) / std::max(1e-300, t[k] - t[k - 1]);
  return y[k - 1] + f * (y[k] - y[k - 1]);
}

// The load curve as the run's load sensor saw it: its [stop] load walls' stored force and
// displacement series read by the one load rule (PinReading), row by row.
analysis::LoadCurve pin_curve(const RunFile& file, const std::vector<std::string>& load_walls, const Vec3& down) {
  analysis::LoadCurve curve;
  curve.time = file.read_series("time");
  std::vector<std::vector<Vec3>> forces, displacements;
  for (const auto& name : load_walls) {
    forces.push_back(file.read_wall_series(name, "force"));
    displacements.push_back(file.read_wall_series(name, "displacement"));
  }
  for (std::size_t k = 0; k < curve.time.size(); ++k) {
    analysis::PinReading pins(down);
    for (std::size_t w = 0; w < load_walls.size(); ++w)
      if (k < forces[w].size() && k < displacements[w].size()) pins.add_wall(forces[w][k], displacements[w][k]);
    curve.force.push_back(pins.force());
    curve.displacement.push_back(pins.displacement());
  }
  return curve;
}

toml::table stored_scene(const std::filesystem::path& path, const RunMetadata& meta) {
  try {
    return toml::parse(meta.scene_text);
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(fmt::format("{}: the stored scene does not parse: {}", path.string(), e.what()));
  }
}

// The scene's cylinder walls: the two loading pins (its [stop] load walls) and the supports (the others).
struct PinsAndSupports {
  std::vector<std::string> load_walls;
  std::vector<CylinderWall> pins, supports;
};

PinsAndSupports pins_and_supports(const toml::table& scene, const std::filesystem::path& path) {
  PinsAndSupports out;
  if (const auto* a = scene["stop"]["load_walls"].as_array())
    for (const auto& n : *a) out.load_walls.push_back(n.value_or(std::string()));
  if (const auto* walls = scene["wall"].as_array())
    for (const auto& w : *walls) {
      const auto* t = w.as_table();
      if (!t || (*t)["shape"].value_or(std::string()) != "cylinder") continue;
      CylinderWall c{(*t)["name"].value_or(std::string()), toml_vec3((*t)["point"].node(), Vec3::Zero())};
      const bool pin = std::find(out.load_walls.begin(), out.load_walls.end(), c.name) != out.load_walls.end();
      (pin ? out.pins : out.supports).push_back(c);
    }
  if (out.pins.size() != 2)
    throw std::runtime_error(fmt::format("{}: a four-point bending run needs two cylinder walls in [stop] load_walls; "
                                         "found {}", path.string(), out.pins.size()));
  return out;
}

// The beam's frame from the pins, and its pin distance and span (given, or from the walls);
// returns where each came from for the report.
std::string frame_and_spans(const std::filesystem::path& path, const PinsAndSupports& walls,
                            const BendingOptions& options, BeamFrame& frame, BendingReport& r) {
  try {
    frame = beam_frame(walls.pins[0].point, walls.pins[1].point, r.down);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(fmt::format("{}: {}", path.string(), e.what()));
  }
  r.axis = frame.axis;
  r.centre = frame.centre;
  std::string source;
  BendingGeometry& g = r.geometry;
  g.pin_distance = options.pin_distance.value_or(distance_along(frame, walls.pins[0].point, walls.pins[1].point));
  source += options.pin_distance ? "pin distance: given; " : "pin distance: pin walls; ";
  if (options.span) {
    g.span = *options.span;
    source += "span: given; ";
  } else if (walls.supports.size() == 2) {
    g.span = distance_along(frame, walls.supports[0].point, walls.supports[1].point);
    source += "span: support walls; ";
  } else {
    throw std::runtime_error(fmt::format("{}: cannot infer the span: {} cylinder walls besides the pins (need 2); "
                                         "give it explicitly", path.string(), walls.supports.size()));
  }
  return source;
}

// The specimen from the first frame: its counts, mean diameter, length, and width and height
// (given, or the spheres' extent) completing the geometry, which is then checked.
SphereExtent read_specimen(const std::filesystem::path& path, const FrameData& first, const BeamFrame& frame,
                           const BendingOptions& options, std::string source, BendingReport& r) {
  r.particles = first.id.size();
  r.bonds = first.bond_i.size();
  if (r.particles == 0) throw std::runtime_error(fmt::format("{}: the first frame holds no particles", path.string()));
  const SphereExtent extent = sphere_extent(frame, first.position, first.radius);
  double dsum = 0;
  for (double rad : first.radius) dsum += 2 * rad;
  r.mean_diameter = dsum / static_cast<double>(r.particles);
  r.length = extent.length;
  BendingGeometry& g = r.geometry;
  g.width = options.width.value_or(extent.width);
  g.height = options.height.value_or(extent.height);
  source += options.width ? "width: given; " : "width: sphere extent; ";
  source += options.height ? "height: given" : "height: sphere extent";
  r.geometry_source = source;
  g.check();
  return extent;
}

// Fragments in the last frame, with the particle masses the frame gives (each of its material).
FragmentSummary last_frame_fragments(const FrameData& last, const BendingOptions& options) {
  FragmentSummary out;
  const analysis::ParticleSample sample{last.id, last.position, last.velocity, last.radius, last.mass, {}};
  const auto fa = analysis::analyse_fragments(sample, {last.bond_i, last.bond_j});
  double total = 0;
  for (const auto& f : fa.fragments) total += f.mass;
  out.count = fa.fragments.size();
  out.frame_time = last.time;
  for (const auto& f : fa.fragments) out.sizes.push_back(f.d_eq);
  for (const auto& f : fa.fragments)
    if (total > 0 && f.mass >= options.major_fragment * total) out.major_mass_fractions.push_back(f.mass / total);
  out.major = out.major_mass_fractions.size();
  return out;
}

// The network's own stiffness: the Voigt estimate of the first frame's bonds.
void network_stiffness(const FrameData& first, BendingReport& r) {
  const BendingGeometry& g = r.geometry;
  const double volume = r.length * g.width * g.height;
  r.voigt = voigt_modulus(first.position, first.radius, first.bond_i, first.bond_j, r.bond, volume, r.axis);
  const double e_over_g = 2.0 * (1.0 + std::clamp(r.voigt.poisson_ratio, 0.0, 0.49));
  r.shear_correction = shear_to_bending_deflection(g, e_over_g);
}

// Local instrumentation: the beam's own deflection under the pins relative to the supports,
// and the curvature between the pins, on every frame before the first break and the peak. The
// first break is the first beyond BendingOptions::local_damage_limit (none allowed by default).
void local_instrumentation(const RunFile& file, const FrameData& first, const SphereExtent& extent,
                           const std::vector<BondBreakEvent>& events, const BendingOptions& options, BendingReport& r) {
  const BendingGeometry& g = r.geometry;
  const auto& time = r.curve.time;
  const auto allowed = static_cast<std::size_t>(std::floor(options.local_damage_limit * static_cast<double>(r.bonds)));
  const double t_first_break = events.size() > allowed ? events[allowed].time : 1e300;
  const double t_peak = time.empty() ? 0 : time[r.analysis.peak_row];
  SectionGauges gauges;
  gauges.centre = r.centre + extent.mid_height * r.down;
  gauges.axis = r.axis;
  gauges.down = r.down;
  gauges.section_width = options.gauge_section > 0 ? options.gauge_section : 2 * r.mean_diameter;
  gauges.core_height = options.gauge_core > 0 ? options.gauge_core : 0.5 * g.height;
  std::map<Index, std::size_t> row_of;
  for (std::size_t k = 0; k < first.id.size(); ++k) row_of[first.id[k]] = k;
  std::vector<LocalFrame> rows;  // before the first break and the peak: the elastic part
  std::vector<Vec3> ref, def;
  for (std::size_t k = 1; k < file.frame_count(); ++k) {
    const FrameData f = file.read_frame(k);
    ref.clear(), def.clear();
    for (std::size_t q = 0; q < f.id.size(); ++q)
      if (auto it = row_of.find(f.id[q]); it != row_of.end()) {
        ref.push_back(first.position[it->second]);
        def.push_back(f.position[q]);
      }
    LocalFrame row;
    row.time = f.time;
    row.force = interpolate(time, r.curve.force, f.time);
    row.deflection = local_deflection(ref, def, gauges, g);
    r.local_curve.time.push_back(row.time);
    r.local_curve.displacement.push_back(row.deflection);
    r.local_curve.force.push_back(row.force);
    if (f.time >= t_first_break || f.time > t_peak) continue;
    row.curvature = curvature_modulus(ref, def, r.centre, r.axis, r.down, g, row.force).curvature;
    rows.push_back(row);
  }
  r.gauges = fit_local_instrumentation(std::move(rows), g, r.analysis.force_max, options.curve);
  r.gauges.breaks_allowed = allowed;  // for the report's wording
  r.predicted_local_stiffness =
      r.gauges.curvature_modulus > 0
          ? predicted_local_stiffness(g, r.gauges.curvature_modulus, std::clamp(r.voigt.poisson_ratio, 0.0, 0.49))
          : 0.0;
}

// Quasi-static check: kinetic against stored elastic energy while loading, before damage.
void quasi_static_check(const RunFile& file, BendingReport& r) {
  const auto& time = r.curve.time;
  const auto ke = file.read_series("kinetic_energy");
  const auto eb = file.read_series("bond_energy");
  const auto ec = file.read_series("contact_energy");
  const auto broken = file.read_series("bonds_broken");
  if (r.analysis.peak_row < broken.size()) r.breaks_before_peak = static_cast<std::size_t>(broken[r.analysis.peak_row]);
  std::size_t loading_rows = 0;  // before the first break and up to the peak
  while (loading_rows < std::min({time.size(), ke.size(), eb.size(), ec.size(), broken.size()}) &&
         broken[loading_rows] == 0 && loading_rows <= r.analysis.peak_row)
    ++loading_rows;
  std::vector<double> elastic(loading_rows);
  for (std::size_t k = 0; k < loading_rows; ++k) elastic[k] = eb[k] + ec[k];
  r.quasi_static.max_kinetic_to_elastic =
      analysis::max_kinetic_to_elastic(std::span(r.curve.force).first(std::min(loading_rows, r.curve.force.size())),
                                       std::span(ke).first(loading_rows), elastic, r.analysis.force_max);
  if (time.size() >= 2 && time.back() > time.front())
    r.quasi_static.loading_speed = (r.curve.displacement.back() - r.curve.displacement.front()) / (time.back() - time.front());
  if (r.quasi_static.loading_speed > 0)
    r.quasi_static.load_time = r.analysis.deflection_at_peak / r.quasi_static.loading_speed;
}

}  // namespace

BendingReport analyse_bending_run(const std::filesystem::path& path, const BendingOptions& options) {
  const RunFile file(path);
  BendingReport r;
  r.run = path;
  const RunMetadata meta = file.metadata();
  const toml::table scene = stored_scene(path, meta);
  r.bond = bond_parameters(meta);
  r.breakage = scene["simulation"]["breakage"].value_or(true) && r.bond.breakage;

  // Loading pins and supports, and the beam's frame and spans from them.
  const PinsAndSupports walls = pins_and_supports(scene, path);
  r.down = toml_vec3(scene["stop"]["load_direction"].node(), -Vec3::UnitZ()).normalized();
  BeamFrame frame;
  std::string source = frame_and_spans(path, walls, options, frame, r);

  if (file.frame_count() == 0) throw std::runtime_error(fmt::format("{}: no frames", path.string()));
  const FrameData first = file.read_frame(0);
  const SphereExtent extent = read_specimen(path, first, frame, options, std::move(source), r);

  r.curve = pin_curve(file, walls.load_walls, r.down);
  r.analysis = analyse_curve(r.curve.displacement, r.curve.force, r.geometry, options.curve);

  // Crack.
  const auto events = file.read_break_events();
  std::vector<Vec3> mids;
  mids.reserve(events.size());
  for (const auto& e : events) mids.push_back(e.midpoint);
  const double window = options.crack_window > 0 ? options.crack_window : 2 * r.mean_diameter;
  r.crack = locate_crack(mids, r.centre, r.axis, window, r.geometry.pin_distance);

  r.fragments = last_frame_fragments(file.read_frame(file.frame_count() - 1), options);
  network_stiffness(first, r);
  local_instrumentation(file, first, extent, events, options, r);
  quasi_static_check(file, r);
  return r;
}

}  // namespace shard::bending
