#include "impact_tracker.hpp"

#include <algorithm>

#include "shard/simulation.hpp"
#include "shard/wall.hpp"

namespace shard::driver::detail {
namespace {
constexpr std::size_t kOffer = 6;  // numbers per offer: body, wall, sphere id, normal
}  // namespace

ImpactTracker::ImpactTracker(const BodyCount& bodies) {
  impacts_.resize(bodies.bodies);
  candidate_.resize(impacts_.size());
  slot_.resize(impacts_.size());
  remaining_ = impacts_.size();
  bodies_known_ = bodies.known;
}

void ImpactTracker::restore(const std::vector<double>& state) {
  impacts_ = impacts_from_state(state, impacts_.size());
  remaining_ = static_cast<std::size_t>(
      std::count_if(impacts_.begin(), impacts_.end(), [](const BodyImpact& i) { return !i.hit; }));
  last_step_ = -1;
}

void ImpactTracker::offer(std::size_t body, std::int32_t wall, Index id, const Vec3& normal) {
  if (impacts_[body].hit) return;
  Candidate& c = candidate_[body];
  if (c.wall < 0) {
    pending_.push_back(body);
  } else if (wall > c.wall || (wall == c.wall && id > c.id)) {
    return;
  }
  c = {wall, id, normal};
}

void ImpactTracker::update(const RunBackend& run) {
  const std::int64_t step = run.local().step_count();
  const bool follows = last_step_ >= 0 && step == last_step_ + 1;
  last_step_ = step;
  // The same on every rank (the table is): all ranks leave here or none does.
  if (remaining_ == 0 || !bodies_known_) return;
  if (follows && run.wall_contacts_begun_anywhere() == 0) return;
  std::vector<double> mine;
  if (follows) {
    // A body without an impact touched no wall but its carriers at the last step, so every
    // contact it has now with another wall began in this step.
    const std::vector<Wall>& walls = run.local().walls();
    for (const auto& c : run.wall_contacts_begun()) {
      if (carries_bodies(walls[static_cast<std::size_t>(c.wall)]) || impacts_[static_cast<std::size_t>(c.body)].hit)
        continue;
      mine.insert(mine.end(), {static_cast<double>(c.body), static_cast<double>(c.wall), static_cast<double>(c.id),
                               c.normal.x(), c.normal.y(), c.normal.z()});
    }
  } else {
    scan(run, mine);
  }
  const std::vector<double> all = run.gather_over_ranks(mine);
  for (std::size_t k = 0; k + kOffer <= all.size(); k += kOffer) {
    const double* o = all.data() + k;
    offer(static_cast<std::size_t>(o[0]), static_cast<std::int32_t>(o[1]), static_cast<Index>(o[2]),
          Vec3(o[3], o[4], o[5]));
  }
  if (!pending_.empty()) record(run);
}

// This rank's own spheres of the bodies without an impact against every wall that does not carry
// them, with the kernel's contact condition (within reach and closer than the radius). No body's
// bounding sphere prunes it (that would take a reduction of its own): it runs once per run and
// restart.
void ImpactTracker::scan(const RunBackend& run, std::vector<double>& offers) const {
  const Particles& p = run.local().particles();
  const std::vector<Wall>& walls = run.local().walls();
  // A serial state from before particle ids names a sphere by its row (run_backend.hpp).
  const auto id = [&p](std::size_t k) { return p.id.size() == p.size() ? p.id[k] : static_cast<Index>(k); };
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (carries_bodies(walls[w])) continue;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (!run.owns(k) || impacts_[static_cast<std::size_t>(p.body[k])].hit) continue;
      Vec3 normal;
      double distance = 0;
      if (!wall_contact(walls[w], p.position[k], p.radius[k], normal, distance) || distance >= p.radius[k]) continue;
      offers.insert(offers.end(), {static_cast<double>(p.body[k]), static_cast<double>(w), static_cast<double>(id(k)),
                                   normal.x(), normal.y(), normal.z()});
    }
  }
}

// The pending bodies' impacts: mass and momentum of each over this rank's own spheres, summed over
// the ranks in rank order.
void ImpactTracker::record(const RunBackend& run) {
  std::sort(pending_.begin(), pending_.end());
  std::vector<std::size_t>& slot = slot_;
  std::fill(slot.begin(), slot.end(), pending_.size());
  for (std::size_t s = 0; s < pending_.size(); ++s) slot[pending_[s]] = s;
  std::vector<double> moments(4 * pending_.size(), 0.0);  // per pending body: mass, momentum
  const Particles& p = run.local().particles();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const std::size_t s = slot[static_cast<std::size_t>(p.body[k])];
    if (s == pending_.size() || !run.owns(k)) continue;
    const Vec3 momentum = p.mass[k] * p.velocity[k];
    moments[4 * s] += p.mass[k];
    for (int a = 0; a < 3; ++a) moments[4 * s + 1 + static_cast<std::size_t>(a)] += momentum[a];
  }
  const std::vector<double> total = run.sum_over_ranks(moments);
  for (std::size_t s = 0; s < pending_.size(); ++s) {
    const std::size_t b = pending_[s];
    Candidate& c = candidate_[b];
    BodyImpact& hit = impacts_[b];
    hit.hit = true;
    hit.step = run.local().step_count();
    hit.time = run.local().time();
    hit.velocity = Vec3(total[4 * s + 1], total[4 * s + 2], total[4 * s + 3]) / total[4 * s];
    hit.normal = c.normal;
    hit.wall = c.wall;
    --remaining_;
    c = Candidate{};
  }
  pending_.clear();
}

}  // namespace shard::driver::detail
