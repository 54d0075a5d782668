#include "shard/analysis/components.hpp"

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/connected_components.hpp>
#include <boost/property_map/property_map.hpp>

namespace shard::analysis {

Index CsrComponentLabeller::label(std::size_t particle_count, const BondList& bonds,
                                  std::vector<Index>& labels) {
  check_bonds(particle_count, bonds);
  // connected_components needs an undirected view; a directed CSR graph holding each bond in
  // both directions is that view.
  using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
                                                   boost::no_property, boost::no_property,
                                                   std::uint32_t, std::uint32_t>;
  const std::size_t m = bonds.size();
  sources_.resize(2 * m);
  targets_.resize(2 * m);
  for (std::size_t k = 0; k < m; ++k) {
    const auto a = static_cast<std::uint32_t>(bonds.i[k]);
    const auto b = static_cast<std::uint32_t>(bonds.j[k]);
    sources_[2 * k] = a;
    targets_[2 * k] = b;
    sources_[2 * k + 1] = b;
    targets_[2 * k + 1] = a;
  }
  const auto n = static_cast<std::uint32_t>(particle_count);
  const Graph graph(boost::construct_inplace_from_sources_and_targets, sources_, targets_, n);
  labels.resize(particle_count);
  const auto components = boost::connected_components(
      graph, boost::make_iterator_property_map(labels.begin(), boost::get(boost::vertex_index, graph)));
  return static_cast<Index>(components);
}

}  // namespace shard::analysis
