#include "body_placement.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "shard/geometry/random.hpp"

namespace shard::scene_detail {
namespace {

Quat axis_angle(const Vec3& axis, double degrees) {
  return Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()));
}

// Uniformly distributed over all rotations (Shoemake's subgroup algorithm).
Quat random_rotation(geometry::Random& rng) {
  const double u1 = rng.uniform(), u2 = 2 * std::numbers::pi * rng.uniform(), u3 = 2 * std::numbers::pi * rng.uniform();
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return Quat(a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3)).normalized();
}

struct Pose {
  bool moved = false;  // false: positions kept bit for bit
  Quat rotation = Quat::Identity();
  Vec3 centre = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 omega = Vec3::Zero();
};

void append(const GeneratedBody& packing, const Vec3& com, const Pose& pose, std::int32_t id, PlacedBodies& out) {
  const auto offset = static_cast<Index>(out.all.position.size());
  const Mat3 r = pose.rotation.toRotationMatrix();
  for (std::size_t k = 0; k < packing.position.size(); ++k) {
    const Vec3 x = pose.moved ? Vec3(pose.centre + r * (packing.position[k] - com)) : packing.position[k];
    out.all.position.push_back(x);
    out.all.radius.push_back(packing.radius[k]);
    out.all.material.push_back(packing.material.empty() ? 0 : packing.material[k]);
    const Vec3 c = pose.moved ? pose.centre : com;
    out.velocity.push_back(pose.omega.isZero() ? pose.velocity : Vec3(pose.velocity + pose.omega.cross(x - c)));
    out.omega.push_back(pose.omega);
    out.body.push_back(id);
  }
  // Bonds only inside the packing: a body's bonds never reach another body.
  for (const auto& [i, j] : packing.bonds) out.all.bonds.emplace_back(i + offset, j + offset);
}

}  // namespace

Vec3 centre_of_mass(const GeneratedBody& packing) {
  Vec3 sum = Vec3::Zero();
  double weight = 0;
  for (std::size_t k = 0; k < packing.position.size(); ++k) {
    const double w = packing.radius[k] * packing.radius[k] * packing.radius[k];
    sum += w * packing.position[k];
    weight += w;
  }
  return sum / weight;
}

void place_body(const BodySpec& spec, std::size_t spec_index, const GeneratedBody& packing, PlacedBodies& out) {
  const Vec3 com = centre_of_mass(packing);
  const BodyPlacement& p = spec.placement;
  const Quat turn = axis_angle(p.rotation_axis, p.rotation_angle);
  if (!spec.stream) {
    Pose pose;
    pose.moved = p.position.has_value() || p.rotation_angle != 0;
    pose.rotation = turn;
    pose.centre = p.position.value_or(com);
    pose.velocity = p.velocity;
    pose.omega = p.angular_velocity;
    out.body_names.push_back(spec.name);
    out.spec_of.push_back(spec_index);
    append(packing, com, pose, static_cast<std::int32_t>(out.body_names.size() - 1), out);
    return;
  }
  const BodyStream& s = *spec.stream;
  geometry::Random rng(s.seed);
  // Bounding radius about the centre of mass: copies whose centres are two of it apart cannot
  // overlap in any orientation.
  double bound = 0;
  for (std::size_t k = 0; k < packing.position.size(); ++k)
    bound = std::max(bound, (packing.position[k] - com).norm() + packing.radius[k]);
  std::vector<Vec3> centres;
  for (std::size_t k = 0; k < s.copies; ++k) {
    Pose pose;
    pose.moved = true;
    // Draw order fixed per copy (rotation, position, speed) so the poses depend only on the seed.
    pose.rotation = s.random_orientation ? random_rotation(rng) : turn;
    if (s.in_region) {
      constexpr int kTries = 1000;
      bool placed = false;
      for (int attempt = 0; attempt < kTries && !placed; ++attempt) {
        for (int a = 0; a < 3; ++a) pose.centre[a] = rng.uniform(s.region_min[a], s.region_max[a]);
        placed = std::all_of(centres.begin(), centres.end(),
                             [&](const Vec3& c) { return (c - pose.centre).norm() >= 2 * bound; });
      }
      if (!placed)
        throw SceneError(fmt::format(
            "{}: [body.stream] of '{}': the region cannot fit {} copies: copy {} found no place at least one "
            "bounding diameter ({:.4g} m) from the others in {} tries; enlarge region_min/region_max or lower copies",
            spec.where, spec.name, s.copies, k, 2 * bound, kTries));
    } else {
      Vec3 jitter;
      for (int a = 0; a < 3; ++a) jitter[a] = rng.uniform(-s.jitter[a], s.jitter[a]);
      pose.centre = s.start + static_cast<double>(k) * s.spacing + jitter;
    }
    centres.push_back(pose.centre);
    pose.velocity = p.velocity * rng.uniform(1 - s.speed_scatter, 1 + s.speed_scatter);
    pose.omega = p.angular_velocity;
    out.body_names.push_back(fmt::format("{}#{}", spec.name, k));
    out.spec_of.push_back(spec_index);
    append(packing, com, pose, static_cast<std::int32_t>(out.body_names.size() - 1), out);
  }
}

void check_body_overlaps(const PlacedBodies& placed, const std::vector<BodySpec>& specs) {
  const auto& x = placed.all.position;
  const auto& r = placed.all.radius;
  const std::size_t n = x.size();
  if (placed.body_names.size() < 2 || n == 0) return;
  double r_max = 0;
  for (double v : r) r_max = std::max(r_max, v);
  const double cell = 2 * r_max;
  // Cells of side 2 r_max hashed by their integer coordinates: overlapping spheres lie in the
  // same or a neighbouring cell.
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::uint64_t>(i) * 73856093u ^ static_cast<std::uint64_t>(j) * 19349663u ^
           static_cast<std::uint64_t>(k) * 83492791u;
  };
  const auto coordinate = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  for (std::size_t p = 0; p < n; ++p) cells[key(coordinate(x[p].x()), coordinate(x[p].y()), coordinate(x[p].z()))].push_back(p);
  for (std::size_t p = 0; p < n; ++p) {
    const std::int64_t ci = coordinate(x[p].x()), cj = coordinate(x[p].y()), ck = coordinate(x[p].z());
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t dk = -1; dk <= 1; ++dk) {
          const auto found = cells.find(key(ci + di, cj + dj, ck + dk));
          if (found == cells.end()) continue;
          for (std::size_t q : found->second) {
            if (q <= p || placed.body[q] == placed.body[p]) continue;
            const double overlap = r[p] + r[q] - (x[p] - x[q]).norm();
            if (overlap <= kBodyOverlapTolerance * std::min(r[p], r[q])) continue;
            const auto a = static_cast<std::size_t>(placed.body[p]), b = static_cast<std::size_t>(placed.body[q]);
            const BodySpec& sa = specs[placed.spec_of[a]];
            const BodySpec& sb = specs[placed.spec_of[b]];
            std::string fix = "move the bodies apart (position) or turn them (rotation_axis, rotation_angle)";
            if (&sa == &sb && sa.stream)
              fix = fmt::format("the stream cannot fit its copies: increase [body.stream] spacing (now {:.4g} m per "
                                "copy) or lower jitter and copies",
                                sa.stream->spacing.norm());
            throw SceneError(fmt::format(
                "{}: [[body]] '{}' and {}: [[body]] '{}' overlap at placement: spheres at [{:.4g}, {:.4g}, {:.4g}] "
                "and [{:.4g}, {:.4g}, {:.4g}] m overlap by {:.3g} m (allowed: {} of the smaller radius); {}",
                sa.where, placed.body_names[a], sb.where, placed.body_names[b], x[p].x(), x[p].y(), x[p].z(),
                x[q].x(), x[q].y(), x[q].z(), overlap, kBodyOverlapTolerance, fix));
          }
        }
  }
}

}  // namespace shard::scene_detail
