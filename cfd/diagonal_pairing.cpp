#include "cfd/diagonal_pairing.hpp"

#include "cfd/sparse_lookup.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <utility>

namespace plumekit::cfd {
namespace {

bool has_entry(const Eigen::SparseMatrix<double>& a, int row, int col) {
  return entry_index(a, row, col) >= 0;
}

// Each cell's candidate faces, in order of preference: east, north, west,
// south. A face qualifies when the pair of swapped rows both have a diagonal:
// the cell's continuity row holds the face, and the face's momentum row holds
// the cell's pressure. A pinned pressure (closed box) has a diagonal already
// and takes no face.
struct Candidates {
  std::vector<int> cells;                 // pressure columns to pair
  std::vector<std::array<int, 4>> faces;  // their faces' columns, -1: none
};
Candidates candidate_faces(const StaggeredGrid& grid, const Eigen::SparseMatrix<double>& jacobian) {
  const GridShape& s = grid.shape();
  Candidates out;
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const int p = grid.pressure_column(s.index(i, j));
      if (p < 0 || has_entry(jacobian, p, p)) continue;
      const std::array<int, 4> faces{
          grid.column(0, grid.face(0, i + 1, j)), grid.column(1, grid.face(1, j + 1, i)),
          grid.column(0, grid.face(0, i, j)), grid.column(1, grid.face(1, j, i))};
      std::array<int, 4> ok{-1, -1, -1, -1};
      int m = 0;
      for (int f : faces)
        if (f >= 0 && has_entry(jacobian, p, f) && has_entry(jacobian, f, p)) ok[m++] = f;
      out.cells.push_back(p);
      out.faces.push_back(ok);
    }
  return out;
}

// Maximum matching of cells to faces (n columns): greedy, then augmenting
// paths found breadth-first (no recursion, so no depth limit on large grids).
// Each cell's face, -1 where none is free; `unpaired` counts those.
std::vector<int> match_faces(const std::vector<std::array<int, 4>>& candidates, int n,
                             int& unpaired) {
  const int nc = static_cast<int>(candidates.size());
  std::vector<int> face_owner(n, -1), cell_face(nc, -1);
  for (int c = 0; c < nc; ++c)
    for (int f : candidates[c])
      if (f >= 0 && face_owner[f] < 0) {
        face_owner[f] = c, cell_face[c] = f;
        break;
      }
  std::vector<int> came_from(n, -1), seen(n, -1), queue;
  for (int start = 0; start < nc; ++start) {
    if (cell_face[start] >= 0) continue;
    queue.assign(1, start);
    int free_face = -1;
    for (std::size_t q = 0; q < queue.size() && free_face < 0; ++q) {
      const int c = queue[q];
      for (int f : candidates[c]) {
        if (f < 0 || seen[f] == start) continue;
        seen[f] = start;
        came_from[f] = c;
        if (face_owner[f] < 0) {
          free_face = f;
          break;
        }
        queue.push_back(face_owner[f]);
      }
    }
    if (free_face < 0) {
      ++unpaired;
      continue;
    }
    // Flip the path: each cell on it takes the face that led to it.
    for (int f = free_face; f >= 0;) {
      const int c = came_from[f];
      const int previous = cell_face[c];
      face_owner[f] = c, cell_face[c] = f;
      f = previous;
    }
  }
  return cell_face;
}

}  // namespace

DiagonalPairing::DiagonalPairing(const StaggeredGrid& grid,
                                 const Eigen::SparseMatrix<double>& jacobian) {
  const int n = static_cast<int>(jacobian.rows());
  const Candidates candidates = candidate_faces(grid, jacobian);
  const std::vector<int> cell_face = match_faces(candidates.faces, n, unpaired_);
  source_row_.resize(n);
  std::iota(source_row_.begin(), source_row_.end(), 0);
  for (std::size_t c = 0; c < cell_face.size(); ++c)
    if (const int f = cell_face[c]; f >= 0)
      std::swap(source_row_[candidates.cells[c]], source_row_[f]);
  build_permuted_pattern(jacobian);
}

void DiagonalPairing::build_permuted_pattern(const Eigen::SparseMatrix<double>& jacobian) {
  // Built straight into compressed columns. The permutation is a set of
  // swaps, so old row r moves to row source_row_[r].
  const int n = static_cast<int>(jacobian.rows());
  permuted_.resize(n, n);
  permuted_.resizeNonZeros(jacobian.nonZeros());
  value_map_.resize(jacobian.nonZeros());
  std::vector<std::pair<int, int>> column;  // (new row, old value index)
  int* outer = permuted_.outerIndexPtr();
  for (int col = 0; col < n; ++col) {
    column.clear();
    for (int k = jacobian.outerIndexPtr()[col]; k < jacobian.outerIndexPtr()[col + 1]; ++k)
      column.emplace_back(source_row_[jacobian.innerIndexPtr()[k]], k);
    std::sort(column.begin(), column.end());
    outer[col] = jacobian.outerIndexPtr()[col];
    for (std::size_t e = 0; e < column.size(); ++e) {
      permuted_.innerIndexPtr()[outer[col] + e] = column[e].first;
      value_map_[column[e].second] = outer[col] + static_cast<int>(e);
    }
  }
  outer[n] = static_cast<int>(jacobian.nonZeros());
}

const Eigen::SparseMatrix<double>& DiagonalPairing::permuted(
    const Eigen::SparseMatrix<double>& jacobian) {
  const double* from = jacobian.valuePtr();
  double* to = permuted_.valuePtr();
  for (std::size_t k = 0; k < value_map_.size(); ++k)
    to[value_map_[k]] = from[k];
  return permuted_;
}

void DiagonalPairing::permute(const double* b, double* pb) const {
  for (std::size_t r = 0; r < source_row_.size(); ++r)
    pb[r] = b[source_row_[r]];
}

}  // namespace plumekit::cfd
