// DistributedSimulation::label_fragments: the fragments (connected components of the surviving
// bonds) of the whole run without gathering its particles or bonds (docs/explanation/scaling.md).
//  1. Each rank labels its own particles and ghosts through its own bonds (analysis's union-find,
//     the serial labeller's), and names each local component by the smallest stable id in it.
//  2. Components that cross a border meet at a ghost: over the halo links, both ways, each rank
//     tells its neighbours the name of every shared particle's component; each keeps the smaller
//     name. Repeated until no name changes anywhere: a name moves one sub-domain per round, so a
//     fragment spanning k sub-domains in a row settles in at most k rounds (plus the one that
//     finds nothing changed). Each component's name is then the smallest id of its fragment.
//  3. The canonical numbering (analysis::canonicalise_labels: heaviest first, then the smallest
//     id) needs every fragment's mass: one record (name, particles, mass) per fragment and rank
//     goes to rank 0, which numbers them and sends each rank the numbers of its records.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "comm.hpp"
#include "halo.hpp"
#include "shard/analysis/components.hpp"
#include "shard/mpi/distributed_simulation.hpp"

namespace shard::mpi {
namespace {

constexpr int kFragmentNameTag = 7302;

// One rank's share of one fragment: what canonicalise_labels needs of it.
struct FragmentPart {
  Index name = 0;  // the fragment's smallest stable id
  Index particles = 0;
  double mass = 0;
};

// The local rows of the particles (own and ghosts) by stable id.
class RowsById {
 public:
  explicit RowsById(const Particles& p) {
    rows_.reserve(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) rows_.emplace_back(p.id[k], k);
    std::sort(rows_.begin(), rows_.end());
  }
  std::size_t operator()(Index id) const {
    const auto it = std::lower_bound(rows_.begin(), rows_.end(), std::pair<Index, std::size_t>{id, 0});
    if (it == rows_.end() || it->first != id)
      throw std::logic_error(fmt::format("label_fragments: particle id {} is not held on this rank", id));
    return it->second;
  }

 private:
  std::vector<std::pair<Index, std::size_t>> rows_;
};

// Step 1: the local components of own particles and ghosts through this rank's intact bonds, and
// each component's smallest id.
struct LocalComponents {
  std::vector<Index> of_row;  // component per local row
  std::vector<Index> name;    // smallest id per component
};

LocalComponents local_components(const Particles& p, const Bonds& b) {
  const bool flags = b.broken.size() == b.size();
  std::vector<Index> i, j;
  i.reserve(b.size());
  j.reserve(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (flags && b.broken[k] != 0) continue;  // broken, not yet removed: not part of the frame
    i.push_back(b.i[k]);
    j.push_back(b.j[k]);
  }
  LocalComponents c;
  analysis::UnionFindLabeller labeller;
  const Index count = labeller.label(p.size(), {i, j}, c.of_row);
  c.name.assign(static_cast<std::size_t>(count), std::numeric_limits<Index>::max());
  for (std::size_t k = 0; k < p.size(); ++k) {
    Index& n = c.name[static_cast<std::size_t>(c.of_row[k])];
    n = std::min(n, p.id[k]);
  }
  return c;
}

// One round of step 2 over the halo links: each link carries the names of the components of its
// `send` ids, then of its `recv` ids; the other end reads them as its `recv`, then `send` ids.
// Returns whether a name here changed.
bool exchange_names(const std::vector<HaloLink>& links, const RowsById& row_of, LocalComponents& c, MPI_Comm comm) {
  std::vector<std::vector<Index>> out(links.size()), in(links.size());
  std::vector<MPI_Request> requests;
  requests.reserve(2 * links.size());
  const auto name_of = [&](Index id) { return c.name[static_cast<std::size_t>(c.of_row[row_of(id)])]; };
  for (std::size_t l = 0; l < links.size(); ++l) {
    for (Index id : links[l].send) out[l].push_back(name_of(id));
    for (Index id : links[l].recv) out[l].push_back(name_of(id));
    in[l].resize(out[l].size());
    requests.emplace_back();
    MPI_Irecv(in[l].data(), static_cast<int>(in[l].size()), MPI_INT32_T, links[l].rank, kFragmentNameTag, comm,
              &requests.back());
    requests.emplace_back();
    MPI_Isend(out[l].data(), static_cast<int>(out[l].size()), MPI_INT32_T, links[l].rank, kFragmentNameTag, comm,
              &requests.back());
  }
  static_assert(sizeof(Index) == sizeof(std::int32_t));
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  bool changed = false;
  for (std::size_t l = 0; l < links.size(); ++l) {
    const std::size_t recv = links[l].recv.size();
    for (std::size_t k = 0; k < in[l].size(); ++k) {
      const Index id = k < recv ? links[l].recv[k] : links[l].send[k - recv];
      Index& name = c.name[static_cast<std::size_t>(c.of_row[row_of(id)])];
      if (in[l][k] < name) {
        name = in[l][k];
        changed = true;
      }
    }
  }
  return changed;
}

// This rank's own particles in ascending id (the frame's row order, frame_share): one part per
// fragment name, its mass summed in that order, and the part of each particle.
struct OwnParts {
  std::vector<FragmentPart> parts;  // ascending name
  std::vector<std::size_t> part_of;
};

OwnParts own_parts(const Particles& p, const LocalComponents& c) {
  std::vector<std::pair<Index, std::size_t>> own;  // (id, row)
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!(p.flags[k] & kGhost)) own.emplace_back(p.id[k], k);
  std::sort(own.begin(), own.end());
  const auto name_of = [&](std::size_t row) { return c.name[static_cast<std::size_t>(c.of_row[row])]; };
  std::vector<Index> names;
  for (const auto& o : own) names.push_back(name_of(o.second));
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  OwnParts out;
  for (Index n : names) out.parts.push_back({n, 0, 0.0});
  out.part_of.resize(own.size());
  for (std::size_t k = 0; k < own.size(); ++k) {
    const auto at = std::lower_bound(names.begin(), names.end(), name_of(own[k].second)) - names.begin();
    out.part_of[k] = static_cast<std::size_t>(at);
    ++out.parts[out.part_of[k]].particles;
    out.parts[out.part_of[k]].mass += p.mass[own[k].second];
  }
  return out;
}

// Step 3 on rank 0: every rank's parts (in rank order) merged by name, numbered canonically;
// returns the number of each part and fills `sizes` (particles per fragment, largest first).
std::vector<Index> number_parts(const std::vector<FragmentPart>& parts, std::vector<std::size_t>& sizes) {
  std::vector<std::size_t> order(parts.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  // Stable: a fragment's mass is summed in rank order.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return parts[a].name < parts[b].name; });
  std::vector<Index> fragment_of_part(parts.size()), fragment, key;
  std::vector<double> mass;
  std::vector<std::size_t> count;
  for (std::size_t k : order) {
    if (key.empty() || key.back() != parts[k].name) {
      fragment.push_back(static_cast<Index>(key.size()));
      key.push_back(parts[k].name);
      mass.push_back(0);
      count.push_back(0);
    }
    mass.back() += parts[k].mass;
    count.back() += static_cast<std::size_t>(parts[k].particles);
    fragment_of_part[k] = fragment.back();
  }
  analysis::canonicalise_labels(fragment, static_cast<Index>(fragment.size()), mass, key);
  for (Index& f : fragment_of_part) f = fragment[static_cast<std::size_t>(f)];
  sizes = std::move(count);
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  return fragment_of_part;
}

}  // namespace

FragmentLabels DistributedSimulation::label_fragments() const {
  const Particles& p = local_->particles();
  const RowsById row_of(p);
  LocalComponents c = local_components(p, local_->bonds());
  FragmentLabels out;
  for (bool again = true; again;) {
    again = any_rank(exchange_names(halo_->links(), row_of, c, comm_));
    ++out.rounds;
  }
  const OwnParts own = own_parts(p, c);
  const std::vector<FragmentPart> all = gather_to(own.parts, 0, comm_);
  const std::vector<Index> numbers =
      scatter_from_root(rank_ == 0 ? number_parts(all, out.sizes) : std::vector<Index>{}, own.parts.size());
  out.labels.resize(own.part_of.size());
  for (std::size_t k = 0; k < own.part_of.size(); ++k) out.labels[k] = numbers[own.part_of[k]];
  return out;
}

}  // namespace shard::mpi
