#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/connected_components.hpp>
#include <boost/iterator/counting_iterator.hpp>
#include <boost/iterator/transform_iterator.hpp>
#include <boost/property_map/property_map.hpp>
#include <utility>

#include "shard/analysis/components.hpp"

namespace shard::analysis {

namespace {
using Vertex = std::uint32_t;
using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
                                                 boost::no_property, boost::no_property, Vertex,
                                                 Vertex>;

// Directed edge e of the doubled bond list: bond e/2, forwards for even e, backwards for odd e.
// connected_components needs an undirected view; a directed CSR graph holding each bond in both
// directions is that view. Generating the edges on the fly avoids a 2M-entry copy.
struct DirectedEdge {
  const Index* i = nullptr;
  const Index* j = nullptr;
  std::pair<Vertex, Vertex> operator()(std::size_t e) const {
    const auto a = static_cast<Vertex>(i[e / 2]);
    const auto b = static_cast<Vertex>(j[e / 2]);
    return (e % 2 == 0) ? std::pair{a, b} : std::pair{b, a};
  }
};
}  // namespace

Index CsrComponentLabeller::label(std::size_t particle_count, const BondList& bonds,
                                  std::vector<Index>& labels) {
  check_bonds(particle_count, bonds);
  const DirectedEdge edge{bonds.i.data(), bonds.j.data()};
  const auto first = boost::make_transform_iterator(boost::counting_iterator<std::size_t>(0), edge);
  const auto last =
      boost::make_transform_iterator(boost::counting_iterator<std::size_t>(2 * bonds.size()), edge);
  // The multi-pass constructor counts out-degrees in a first pass and scatters in a second:
  // linear time. (The in-place constructor from source/target vectors took ~1.5 s here.)
  const Graph graph(boost::edges_are_unsorted_multi_pass, first, last,
                    static_cast<Vertex>(particle_count));
  labels.resize(particle_count);
  const auto components = boost::connected_components(
      graph, boost::make_iterator_property_map(labels.begin(), boost::get(boost::vertex_index, graph)));
  return static_cast<Index>(components);
}

}  // namespace shard::analysis
