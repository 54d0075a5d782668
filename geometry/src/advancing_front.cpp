// Advancing-front sphere filling (seed sec. III). The front is a min-heap of placed spheres keyed by
// their distance to the seed point; the top sphere is "worked" until no sphere of the pending
// radius fits around it, then it leaves the front. Each sphere enters the front once and leaves it
// once, so the loop runs at most 2N times; the grid keeps each attempt O(1).
#include "shard/geometry/advancing_front.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>

#include "shard/geometry/random.hpp"
#include "shard/geometry/sphere_grid.hpp"

namespace shard::geometry {
namespace {

// Points at distances da, db, dc from a, b, c (three-sphere trilateration): 0, 1 or 2 solutions.
int tangent_positions(const Vec3& a, const Vec3& b, const Vec3& c, double da, double db, double dc,
                      std::array<Vec3, 2>& out) {
  const Vec3 ab = b - a;
  const double d = ab.norm();
  if (!(d > 0.0)) return 0;
  const Vec3 ex = ab / d;
  const Vec3 ac = c - a;
  const double i = ex.dot(ac);
  const Vec3 across = ac - i * ex;
  const double j = across.norm();
  if (j <= 1e-9 * d) return 0;  // collinear centres: a circle of solutions, none isolated
  const Vec3 ey = across / j;
  const Vec3 ez = ex.cross(ey);
  const double x = (da * da - db * db + d * d) / (2.0 * d);
  const double y = (da * da - dc * dc + i * i + j * j) / (2.0 * j) - i * x / j;
  const double z2 = da * da - x * x - y * y;
  if (z2 < 0.0) return 0;
  const double z = std::sqrt(z2);
  const Vec3 base = a + x * ex + y * ey;
  out[0] = base + z * ez;
  out[1] = base - z * ez;
  return z > 0.0 ? 2 : 1;
}

// Points at distances da from a and db from b on the plane n.x = h (|n| = 1): the circle where
// the two spheres meet, cut by the plane. 0, 1 or 2 solutions.
int tangent_positions_on_plane(const Vec3& a, const Vec3& b, double da, double db, const Vec3& n, double h,
                               std::array<Vec3, 2>& out) {
  const Vec3 ab = b - a;
  const double d = ab.norm();
  if (!(d > 0.0)) return 0;
  const Vec3 e = ab / d;
  const double t = (da * da - db * db + d * d) / (2.0 * d);
  const double rho2 = da * da - t * t;
  if (!(rho2 > 0.0)) return 0;
  const double rho = std::sqrt(rho2);
  const Vec3 centre = a + t * e;
  const Vec3 across = n - n.dot(e) * e;
  const double tilt = across.norm();
  if (tilt <= 1e-9) return 0;  // the circle lies parallel to the plane: none or a whole circle
  const Vec3 u = across / tilt;
  const Vec3 v = e.cross(u);
  const double cos_angle = (h - n.dot(centre)) / (rho * tilt);
  if (std::abs(cos_angle) > 1.0) return 0;
  const double sin_angle = std::sqrt(1.0 - cos_angle * cos_angle);
  out[0] = centre + rho * (cos_angle * u + sin_angle * v);
  out[1] = centre + rho * (cos_angle * u - sin_angle * v);
  return sin_angle > 0.0 ? 2 : 1;
}

// The plane that holds the centres of spheres of radius r touching the surface from inside, as
// seen from p: n.x = h with n the outward normal at the surface point nearest p.
struct CentrePlane {
  Vec3 normal;
  double offset;
};

std::optional<CentrePlane> centre_plane_near(const SignedDistance& distance, const Vec3& p, double r, double step) {
  Vec3 gradient;
  for (int k = 0; k < 3; ++k) {
    Vec3 dp = Vec3::Zero();
    dp[k] = step;
    gradient[k] = (distance(p + dp) - distance(p - dp)) / (2.0 * step);
  }
  // A distance field has a unit gradient; a much smaller one means p sits where the field is clamped
  // or on a ridge between two faces, which has no single tangent plane.
  const double norm = gradient.norm();
  if (!(norm > 0.5)) return std::nullopt;
  const Vec3 n = gradient / norm;
  const Vec3 foot = p - distance(p) * n;
  return CentrePlane{n, n.dot(foot) - r};
}

// A sphere placed against the surface may cross it by this fraction of its radius: it absorbs the
// interpolation error of a voxelized signed distance.
constexpr double kSurfaceAllowance = 1e-3;

struct Candidate {
  double key;  // squared distance to the seed point
  Vec3 centre;
  bool touches_surface;
};

class FrontFiller {
 public:
  FrontFiller(const SignedDistance& distance, const Box& bounds, const SizeDistribution& psd,
              const FrontFillOptions& options)
      : distance_(distance),
        bounds_(bounds),
        psd_(psd),
        options_(options),
        rng_(options.seed),
        r_max_(0.5 * psd.d_max()),
        normal_step_(options.normal_step > 0.0 ? options.normal_step : psd.d_min() / 8.0),
        grid_(bounds.lower, bounds.upper, psd.d_max()) {}

  SpherePacking run() {
    place_seed();
    double r = draw_radius();
    while (!front_.empty()) {
      const Index worked = front_.top().second;
      if (const auto spot = best_spot_around(worked, r)) {
        add(*spot, r);
        r = draw_radius();
      } else {
        front_.pop();  // nothing of this size fits around it any more
      }
    }
    return std::move(packing_);
  }

 private:
  double draw_radius() { return 0.5 * psd_.diameter_at(rng_.uniform()); }

  void add(const Vec3& centre, double radius) {
    const auto id = static_cast<Index>(packing_.centre.size());
    packing_.centre.push_back(centre);
    packing_.radius.push_back(radius);
    grid_.insert(id, centre);
    front_.emplace((centre - seed_point_).squaredNorm(), id);
  }

  // Any sphere overlapping a candidate P (|P - c_A| = r_A + r) lies within r_A + r_j + 2r of A,
  // so A's neighbour list is the complete set of possible blockers: no grid query per candidate.
  // Blockers cluster: the sphere that blocked the previous candidate is tried first.
  bool blocked(const Vec3& p, double r) {
    const std::size_t count = near_centre_.size();
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t n = k == 0 ? last_blocker_ : (k == last_blocker_ ? 0 : k);
      const double rj = near_radius_[n];
      const double limit = r + rj - options_.overlap_tolerance * std::min(r, rj);
      if ((near_centre_[n] - p).squaredNorm() < limit * limit) {
        last_blocker_ = n;
        return true;
      }
    }
    return false;
  }

  std::optional<Vec3> best_spot_around(Index a, double r) {
    const Vec3 ca = packing_.centre[a];
    const double ra = packing_.radius[a];
    near_centre_.clear();
    near_radius_.clear();
    grid_.for_each_near(ca, ra + 2.0 * r + r_max_, [&](Index id) {
      if (id != a) {
        const double reach = ra + packing_.radius[id] + 2.0 * r;
        if ((packing_.centre[id] - ca).squaredNorm() < reach * reach) {
          near_centre_.push_back(packing_.centre[id]);
          near_radius_.push_back(packing_.radius[id]);
        }
      }
      return true;
    });
    // Blocked candidates are dropped at once; the free ones are few, and the nearest to the seed
    // among those inside the body wins.
    candidates_.clear();
    last_blocker_ = 0;
    std::array<Vec3, 2> spots;
    for (std::size_t p = 0; p < near_centre_.size(); ++p) {
      const Vec3& cb = near_centre_[p];
      const double rb = near_radius_[p];
      for (std::size_t q = p + 1; q < near_centre_.size(); ++q) {
        const Vec3& cc = near_centre_[q];
        const double rc = near_radius_[q];
        const double reach = rb + rc + 2.0 * r;
        if ((cb - cc).squaredNorm() >= reach * reach) continue;
        const int n = tangent_positions(ca, cb, cc, ra + r, rb + r, rc + r, spots);
        for (int s = 0; s < n; ++s)
          if (!blocked(spots[s], r)) candidates_.push_back({(spots[s] - seed_point_).squaredNorm(), spots[s], false});
      }
    }
    if (options_.conform_to_surface) add_surface_candidates(ca, ra, r);
    // Spots against the surface come first: a sphere the front puts near the surface without
    // touching it would leave a gap no other sphere fits in, and the face would stay rough.
    std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& x, const Candidate& y) {
      if (x.touches_surface != y.touches_surface) return x.touches_surface;
      return x.key < y.key || (x.key == y.key && std::lexicographical_compare(x.centre.data(), x.centre.data() + 3,
                                                                               y.centre.data(), y.centre.data() + 3));
    });
    for (const Candidate& candidate : candidates_)
      if (inside(candidate, r)) return candidate.centre;
    return std::nullopt;
  }

  bool inside(const Candidate& candidate, double r) const {
    const double allowance = candidate.touches_surface ? kSurfaceAllowance * r : 0.0;
    return distance_(candidate.centre) <= -r + allowance;
  }

  // Spots touching the worked sphere A, one neighbour B and the surface. The tangent plane is taken
  // where A's nearest surface point is, then once more at the spot found, so that a curved surface
  // is met where the sphere touches it.
  void add_surface_candidates(const Vec3& ca, double ra, double r) {
    if (-distance_(ca) > ra + 2.0 * r) return;  // a sphere touching A cannot reach the surface
    const auto plane = centre_plane_near(distance_, ca, r, normal_step_);
    if (!plane) return;
    std::array<Vec3, 2> spots;
    std::array<Vec3, 2> refined;
    for (std::size_t p = 0; p < near_centre_.size(); ++p) {
      const Vec3& cb = near_centre_[p];
      const double rb = near_radius_[p];
      const int n = tangent_positions_on_plane(ca, cb, ra + r, rb + r, plane->normal, plane->offset, spots);
      for (int s = 0; s < n; ++s) {
        if (blocked(spots[s], r)) continue;
        const auto local = centre_plane_near(distance_, spots[s], r, normal_step_);
        if (!local) continue;
        const int m = tangent_positions_on_plane(ca, cb, ra + r, rb + r, local->normal, local->offset, refined);
        if (m == 0) continue;
        const Vec3 spot = (m == 2 && (refined[1] - spots[s]).squaredNorm() < (refined[0] - spots[s]).squaredNorm())
                              ? refined[1]
                              : refined[0];
        if (!blocked(spot, r)) candidates_.push_back({(spot - seed_point_).squaredNorm(), spot, true});
      }
    }
  }

  // The seed goes to the deepest points of a probe lattice (ties: nearest the box centre; beyond
  // the narrow band depths are clamped, so several candidates are tried). At each, the first
  // sphere sits on the probe point and the other two touch it in random orientations.
  void place_seed() {
    const double spacing = options_.probe_spacing * psd_.d_max();
    const Vec3 middle = 0.5 * (bounds_.lower + bounds_.upper);
    const Vec3 extent = bounds_.upper - bounds_.lower;
    std::array<long, 3> count{};
    for (int k = 0; k < 3; ++k) count[k] = std::max(1L, static_cast<long>(extent[k] / spacing));
    struct Probe {
      double depth_key;  // signed distance: smaller is deeper
      double offset;
      Vec3 point;
    };
    std::vector<Probe> probes;
    for (long i = 0; i < count[0]; ++i)
      for (long j = 0; j < count[1]; ++j)
        for (long k = 0; k < count[2]; ++k) {
          const Vec3 p = bounds_.lower + Vec3((static_cast<double>(i) + 0.5) * extent.x() / static_cast<double>(count[0]),
                                              (static_cast<double>(j) + 0.5) * extent.y() / static_cast<double>(count[1]),
                                              (static_cast<double>(k) + 0.5) * extent.z() / static_cast<double>(count[2]));
          const double d = distance_(p);
          if (d <= -psd_.d_min() / 2.0) probes.push_back({d, (p - middle).squaredNorm(), p});
        }
    const auto deeper = [](const Probe& a, const Probe& b) {
      return a.depth_key < b.depth_key || (a.depth_key == b.depth_key && a.offset < b.offset);
    };
    const std::size_t tried = std::min<std::size_t>(probes.size(), 16);
    std::partial_sort(probes.begin(), probes.begin() + static_cast<std::ptrdiff_t>(tried), probes.end(), deeper);
    for (std::size_t n = 0; n < tried; ++n) {
      seed_point_ = probes[n].point;
      constexpr int kOrientations = 64;
      for (int attempt = 0; attempt < kOrientations; ++attempt) {
        const std::array<double, 3> r{draw_radius(), draw_radius(), draw_radius()};
        const Vec3 e1 = rng_.direction();
        const Vec3 e2 = e1.cross(rng_.direction()).normalized();
        const double c = r[0] + r[1];
        const double a = r[0] + r[2];
        const double b = r[1] + r[2];
        const double x = (a * a - b * b + c * c) / (2.0 * c);
        const std::array<Vec3, 3> at{seed_point_, Vec3(seed_point_ + c * e1),
                                     Vec3(seed_point_ + x * e1 + std::sqrt(a * a - x * x) * e2)};
        bool inside = true;
        for (int s = 0; s < 3; ++s) inside = inside && distance_(at[s]) <= -r[s];
        if (!inside) continue;
        for (int s = 0; s < 3; ++s) add(at[s], r[s]);
        return;
      }
    }
    throw FillError(fmt::format("the body is too thin for the particle size: its deepest probed point lies "
                                "{:.4g} m inside the surface, and no seed of three touching spheres of diameter "
                                "{:.4g}..{:.4g} m fits there. Reduce the diameters or check the STL scale",
                                probes.empty() ? 0.0 : -probes.front().depth_key, psd_.d_min(), psd_.d_max()));
  }

  const SignedDistance& distance_;
  Box bounds_;
  const SizeDistribution& psd_;
  FrontFillOptions options_;
  Random rng_;
  double r_max_;
  double normal_step_;
  SphereGrid grid_;
  SpherePacking packing_;
  Vec3 seed_point_ = Vec3::Zero();
  using Entry = std::pair<double, Index>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> front_;
  std::vector<Vec3> near_centre_;  // the worked sphere's neighbours, copied contiguously
  std::vector<double> near_radius_;
  std::size_t last_blocker_ = 0;
  std::vector<Candidate> candidates_;
};

}  // namespace

SpherePacking advancing_front_fill(const SignedDistance& distance, const Box& bounds,
                                   const SizeDistribution& psd, const FrontFillOptions& options) {
  return FrontFiller(distance, bounds, psd, options).run();
}

}  // namespace shard::geometry
