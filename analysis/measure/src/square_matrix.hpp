#pragma once
// Square matrices as the measurement library's result types hold them (rows of doubles) and as
// Eigen computes with them.
#include <Eigen/Dense>
#include <stdexcept>
#include <vector>

namespace shard::measure {

inline Eigen::MatrixXd to_matrix(const std::vector<std::vector<double>>& a) {
  const auto n = static_cast<Eigen::Index>(a.size());
  Eigen::MatrixXd m(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (static_cast<Eigen::Index>(a[static_cast<std::size_t>(i)].size()) != n)
      throw std::invalid_argument("contrast: matrix is not square");
    for (Eigen::Index j = 0; j < n; ++j) m(i, j) = a[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  return m;
}

inline std::vector<std::vector<double>> from_matrix(const Eigen::MatrixXd& m) {
  std::vector<std::vector<double>> a(static_cast<std::size_t>(m.rows()), std::vector<double>(static_cast<std::size_t>(m.cols())));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) a[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = m(i, j);
  return a;
}

}  // namespace shard::measure
