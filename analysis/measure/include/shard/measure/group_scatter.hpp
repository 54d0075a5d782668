#pragma once
// The specimens' scatter behind every contrast (docs/explanation/diagnosis.md "Noise").
//
// One fixture and one lab give the sets one scatter structure, so their covariance is pooled
// (contrast.hpp). A batch can break that: rollers without friction let some beams slide and
// others not, and such a set scattered seven times the others' peak force on foreign truth. Pooled
// in, its scatter swamps every other set's contrast (a softening's T^2 fell from 1569 to 44).
// So each group's scatter is first held against the others', component by component: its
// variance over the others' pooled variance is F(n_g - 1, nu) distributed when they scatter
// alike, and its largest ratio is referred to that with Bonferroni over the m components. The most
// exceptional group is set apart while its p is below alpha over the groups, and the pool is
// taken again without it. (Not a whitened trace tr(Sigma^-1 S_g): an effect such as a machine
// compliance moves the specimens along the pool's near-null directions, where the linear rise
// ties stiffness, peak force and peak displacement together, and that trace then set apart
// most sets with an effect, taking their degrees of freedom from the others.)
// A group set apart keeps the pooled correlation with, in each component, the larger of its own
// and the pooled standard deviation: a wider contrast covariance for that set alone. It lowers
// the set's T^2 and its remainders alike, so a remainder can pass as noise that the pool would
// have rejected (a frictionless-roller set of the foreign study is named a wrong effect at 525
// trial sizes unless confirmation runs stay within kFarthestTrialSteps).
#include <cstddef>
#include <vector>

namespace shard::measure {

struct GroupScatter {
  std::vector<std::vector<double>> pooled;  // covariance pooled over the groups not set apart, shrunk
  double dof = 0;                           // sum(n_g - 1) over those groups
  std::vector<double> ratio;         // the largest component variance over the other groups' pooled one
  std::vector<std::size_t> component;       // the component of that ratio
  std::vector<double> p_value;              // of the ratio under one common scatter
  std::vector<bool> own;                    // set apart: the group carries its own scatter
  std::vector<std::vector<std::vector<double>>> covariance;  // per group: the covariance of one specimen
};

// `groups`: rows of components per group (one row per specimen). Groups of one specimen are
// never set apart and never pooled; at least two groups stay pooled.
GroupScatter group_scatter(const std::vector<std::vector<std::vector<double>>>& groups, double shrinkage,
                           double alpha);

}  // namespace shard::measure
