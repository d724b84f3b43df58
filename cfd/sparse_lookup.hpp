#pragma once
// Finding one entry of a compressed-column matrix whose row indices are
// sorted in each column (as Eigen keeps them once compressed).
#include <Eigen/SparseCore>
#include <algorithm>

namespace plumekit::cfd {

// Index of entry (row, col) in a's value array, or -1 when the pattern has none.
inline int entry_index(const Eigen::SparseMatrix<double>& a, int row, int col) {
  const int* begin = a.innerIndexPtr() + a.outerIndexPtr()[col];
  const int* end = a.innerIndexPtr() + a.outerIndexPtr()[col + 1];
  const int* at = std::lower_bound(begin, end, row);
  return at != end && *at == row ? static_cast<int>(at - a.innerIndexPtr()) : -1;
}

}  // namespace plumekit::cfd
