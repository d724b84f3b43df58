#include "cfd/nullspace_solver.hpp"

#include <umfpack.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cfd/sparse_lookup.hpp"

namespace plumekit::cfd {
namespace {

// J(row, col), or 0 when the pattern has no such entry.
double entry(const Eigen::SparseMatrix<double>& a, int row, int col) {
  const int k = entry_index(a, row, col);
  return k >= 0 ? a.valuePtr()[k] : 0.0;
}

// Largest |value| of a sparse matrix's columns [from, to).
double max_abs(const Eigen::SparseMatrix<double>& a, int from, int to) {
  double m = 0.0;
  for (int k = a.outerIndexPtr()[from]; k < a.outerIndexPtr()[to]; ++k)
    m = std::max(m, std::abs(a.valuePtr()[k]));
  return m;
}

// Union-find over grid nodes, with path halving.
struct NodeGroups {
  std::vector<int> parent;
  explicit NodeGroups(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a)
      a = parent[a] = parent[parent[a]];
    return a;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

// Nodes at the two ends of face (a, b) of component c, in the order that
// makes the face's velocity (psi(second) - psi(first)) * scale.
struct FaceEnds {
  int first, second;
  double scale;
};
FaceEnds face_ends(const GridShape& s, int c, int a, int b) {
  const int nodes_x = s.nx + 1;
  auto node = [&](int i, int j) { return j * nodes_x + i; };
  if (c == 0) return {node(a, b), node(a, b + 1), 1.0 / s.dy()};  // u = d psi / dy
  return {node(b + 1, a), node(b, a), 1.0 / s.dx()};              // v = -d psi / dx
}

// Node groups: nodes joined by a fixed face beside a fluid cell share their
// streamfunction correction. Faces inside solid (or between solid and the
// outside) join nothing: an outlet on an obstacle's edge lets flux into the
// obstacle, so the obstacle's outline either side of it must stay apart.
NodeGroups fixed_face_groups(const StaggeredGrid& grid) {
  const GridShape& s = grid.shape();
  NodeGroups groups(static_cast<std::size_t>(s.nx + 1) * (s.ny + 1));
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < grid.n_across(c); ++b)
      for (int a = 0; a <= grid.n_along(c); ++a)
        if (grid.column(c, grid.face(c, a, b)) < 0 && grid.fluid_side(c, a, b) != 0) {
          const FaceEnds e = face_ends(s, c, a, b);
          groups.unite(e.first, e.second);
        }
  return groups;
}

}  // namespace

NullSpaceSolver::NullSpaceSolver(const StaggeredGrid& grid,
                                 const Eigen::SparseMatrix<double>& jacobian, ReducedLU lu)
    : n_(static_cast<int>(jacobian.rows())), n_mom_(grid.velocity_unknowns()) {
  if (!read_continuity_rows(jacobian) || !build_tree(grid, jacobian)) return;
  build_curl(grid);
  {
    const Eigen::SparseMatrix<double> curl_g = build_projection(jacobian);
    applicable_ = operators_check(grid.shape(), jacobian, curl_g);
  }
  const bool single = lu == ReducedLU::Single ||
                      (lu == ReducedLU::BySize && reduced_size() >= kSinglePrecisionFrom);
  if (applicable_ && single && single_precision_lu_available())
    single_ = std::make_unique<SinglePrecisionLU>();
}

bool NullSpaceSolver::read_continuity_rows(const Eigen::SparseMatrix<double>& jacobian) {
  const int* outer = jacobian.outerIndexPtr();
  const int* inner = jacobian.innerIndexPtr();
  const double* value = jacobian.valuePtr();
  // The continuity rows, read from the velocity columns.
  continuity_.resize(n_ - n_mom_);
  for (int col = 0; col < n_mom_; ++col)
    for (int k = outer[col]; k < outer[col + 1]; ++k)
      if (inner[k] >= n_mom_) {
        ContinuityRow& row = continuity_[inner[k] - n_mom_];
        if (row.count == 4) return false;  // not a MAC continuity row
        row.col[row.count] = col;
        row.coef[row.count++] = value[k];
      }
  return true;
}

double NullSpaceSolver::continuity_coef(int p, int col) const {
  const ContinuityRow& row = continuity_[p - n_mom_];
  for (int e = 0; e < row.count; ++e)
    if (row.col[e] == col) return row.coef[e];
  return 0.0;
}

void NullSpaceSolver::add_root(const StaggeredGrid& grid,
                               const Eigen::SparseMatrix<double>& jacobian,
                               std::vector<char>& reached, std::size_t cell, int face) {
  const int p = grid.pressure_column(cell);
  if (p < 0 || reached[cell]) return;
  reached[cell] = 1;
  TreeCell t{static_cast<int>(cell), p, face, -1};
  // A pinned root's own row is its pressure alone: g_own is that coefficient.
  t.g_own = face >= 0 ? entry(jacobian, face, p) : entry(jacobian, p, p);
  if (face >= 0) t.d_face = continuity_coef(p, face);
  tree_.push_back(t);
}

void NullSpaceSolver::add_roots(const StaggeredGrid& grid,
                                const Eigen::SparseMatrix<double>& jacobian,
                                std::vector<char>& reached) {
  const GridShape& s = grid.shape();
  // The cells beside the outlet, through their outlet face.
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const std::size_t faces[4][2] = {{0, grid.face(0, i + 1, j)},
                                       {0, grid.face(0, i, j)},
                                       {1, grid.face(1, j + 1, i)},
                                       {1, grid.face(1, j, i)}};
      for (const auto& f : faces)
        if (grid.kind(static_cast<int>(f[0]), f[1]) == kOutflow) {
          add_root(grid, jacobian, reached, s.index(i, j),
                   grid.column(static_cast<int>(f[0]), f[1]));
          break;
        }
    }
  // A closed box: its pinned cell.
  if (tree_.empty())
    for (std::size_t cell = 0; cell < s.size() && tree_.empty(); ++cell) {
      const int p = grid.pressure_column(cell);
      if (p >= 0 && entry(jacobian, p, p) != 0.0) add_root(grid, jacobian, reached, cell, -1);
    }
}

bool NullSpaceSolver::build_tree(const StaggeredGrid& grid,
                                 const Eigen::SparseMatrix<double>& jacobian) {
  // Spanning tree of the fluid cells through cell-to-cell faces, breadth
  // first from the cells beside the outlet (or the pinned cell).
  const GridShape& s = grid.shape();
  std::vector<char> reached(s.size(), 0);
  add_roots(grid, jacobian, reached);
  for (std::size_t q = 0; q < tree_.size(); ++q) {
    const int i = tree_[q].cell % s.nx, j = tree_[q].cell / s.nx;
    // (neighbour i, j, component, face along, face across)
    const int next[4][5] = {
        {i + 1, j, 0, i + 1, j}, {i - 1, j, 0, i, j}, {i, j + 1, 1, j + 1, i}, {i, j - 1, 1, j, i}};
    for (const auto& nb : next) {
      if (nb[0] < 0 || nb[0] >= s.nx || nb[1] < 0 || nb[1] >= s.ny) continue;
      const std::size_t other = s.index(nb[0], nb[1]);
      const int face = grid.column(nb[2], grid.face(nb[2], nb[3], nb[4]));
      const int p_other = grid.pressure_column(other);
      if (reached[other] || p_other < 0 || face < 0) continue;
      reached[other] = 1;
      TreeCell t{static_cast<int>(other), p_other, face, tree_[q].p};
      t.d_face = continuity_coef(p_other, face);
      t.g_own = entry(jacobian, face, p_other);
      t.g_parent = entry(jacobian, face, tree_[q].p);
      tree_.push_back(t);
    }
  }
  if (static_cast<int>(tree_.size()) != n_ - n_mom_) return false;  // a pocket: no path to the root
  for (const TreeCell& t : tree_)
    if (t.face >= 0 && (t.d_face == 0.0 || t.g_own == 0.0)) return false;
  return true;
}

void NullSpaceSolver::build_curl(const StaggeredGrid& grid) {
  const GridShape& s = grid.shape();
  NodeGroups groups = fixed_face_groups(grid);
  // Only groups at the ends of some unknown face carry a correction (nodes
  // inside solid carry none). The first of them in node order, the walls'
  // group unless an obstacle fills the bottom-left corner, is the gauge.
  std::vector<char> used(groups.parent.size(), 0);
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < grid.n_across(c); ++b)
      for (int a = 0; a <= grid.n_along(c); ++a) {
        if (grid.column(c, grid.face(c, a, b)) < 0) continue;
        const FaceEnds e = face_ends(s, c, a, b);
        const int g1 = groups.find(e.first), g2 = groups.find(e.second);
        if (g1 != g2) used[g1] = used[g2] = 1;
      }
  int gauge = -1;
  std::vector<int> group_col(groups.parent.size(), -1);
  int n_groups = 0;
  for (std::size_t k = 0; k < groups.parent.size(); ++k) {
    const int g = groups.find(static_cast<int>(k));
    if (!used[g]) continue;
    if (gauge < 0) gauge = g;
    if (g != gauge && group_col[g] < 0) group_col[g] = n_groups++;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < grid.n_across(c); ++b)
      for (int a = 0; a <= grid.n_along(c); ++a) {
        const int col = grid.column(c, grid.face(c, a, b));
        if (col < 0) continue;
        const FaceEnds e = face_ends(s, c, a, b);
        const int g1 = groups.find(e.first), g2 = groups.find(e.second);
        if (g1 == g2) continue;  // a dead end: no divergence-free flux through it
        if (group_col[g2] >= 0) triplets.emplace_back(col, group_col[g2], e.scale);
        if (group_col[g1] >= 0) triplets.emplace_back(col, group_col[g1], -e.scale);
      }
  curl_.resize(n_, n_groups);
  curl_.setFromTriplets(triplets.begin(), triplets.end());
}

Eigen::SparseMatrix<double> NullSpaceSolver::build_projection(
    const Eigen::SparseMatrix<double>& jacobian) {
  // L' = C' (I - G R): C' plus, for each outlet face, minus the curl
  // projection of its cell's pressure column over the face's coefficient.
  // Only C' G is formed: the whole C' J took 0.1 s on a 5 cm building grid.
  const Eigen::SparseMatrix<double> curl_t = curl_.transpose();
  Eigen::SparseMatrix<double> curl_g = curl_t * jacobian.rightCols(n_ - n_mom_);  // groups x cells
  std::vector<Eigen::Triplet<double>> triplets;
  for (int col = 0; col < n_mom_; ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(curl_t, col); it; ++it)
      triplets.emplace_back(static_cast<int>(it.row()), col, it.value());
  for (const TreeCell& t : tree_) {
    if (t.parent >= 0 || t.face < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(curl_g, t.p - n_mom_); it; ++it)
      triplets.emplace_back(static_cast<int>(it.row()), t.face, -it.value() / t.g_own);
  }
  left_.resize(curl_.cols(), n_);
  left_.setFromTriplets(triplets.begin(), triplets.end());
  return curl_g;
}

bool NullSpaceSolver::operators_check(const GridShape& s,
                                      const Eigen::SparseMatrix<double>& jacobian,
                                      const Eigen::SparseMatrix<double>& curl_g) const {
  // C is divergence-free: each continuity row of D C, summed group by group
  // over the row's (at most four) faces' curl entries.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> curl_rows = curl_;
  double d_max = 0.0;
  std::vector<std::pair<int, double>> sums;
  for (int p = n_mom_; p < n_; ++p) {
    if (entry(jacobian, p, p) != 0.0) continue;  // the pinned row
    const ContinuityRow& row = continuity_[p - n_mom_];
    sums.clear();
    for (int e = 0; e < row.count; ++e)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(curl_rows, row.col[e]);
           it; ++it) {
        const int g = static_cast<int>(it.col());
        auto at = std::find_if(sums.begin(), sums.end(),
                               [g](const auto& slot) { return slot.first == g; });
        if (at == sums.end()) at = sums.insert(sums.end(), {g, 0.0});
        at->second += row.coef[e] * it.value();
      }
    for (const auto& [g, sum] : sums)
      d_max = std::max(d_max, std::abs(sum));
  }
  // L' removes the pressure: L' G = 0.
  const Eigen::SparseMatrix<double> left_g = left_ * jacobian.rightCols(n_ - n_mom_);
  const double scale =
      max_abs(curl_g, 0, static_cast<int>(curl_g.cols())) + 1.0 / (s.dx() * s.dy());
  return d_max < 1e-9 * scale && max_abs(left_g, 0, static_cast<int>(left_g.cols())) < 1e-9 * scale;
}

void NullSpaceSolver::build_reduced_pattern(const Eigen::SparseMatrix<double>& jacobian) {
  // Column g of K holds the groups that L' J reaches from g's curl faces.
  const int groups = reduced_size();
  const int* j_outer = jacobian.outerIndexPtr();
  const int* j_inner = jacobian.innerIndexPtr();
  std::vector<int> mark(groups, -1), outer(groups + 1, 0), inner, rows;
  for (int col = 0; col < groups; ++col) {
    rows.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator c(curl_, col); c; ++c)
      for (int k = j_outer[c.row()]; k < j_outer[c.row() + 1]; ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator l(left_, j_inner[k]); l; ++l)
          if (mark[l.row()] != col) {
            mark[l.row()] = col;
            rows.push_back(static_cast<int>(l.row()));
          }
    std::sort(rows.begin(), rows.end());
    inner.insert(inner.end(), rows.begin(), rows.end());
    outer[col + 1] = static_cast<int>(inner.size());
  }
  const std::vector<double> zeros(inner.size(), 0.0);
  reduced_ = Eigen::Map<const Eigen::SparseMatrix<double>>(
      groups, groups, static_cast<Eigen::Index>(inner.size()), outer.data(), inner.data(),
      zeros.data());
  slot_.assign(groups, -1);
  jc_.assign(n_, 0.0);
  in_column_.assign(n_, 0);
}

void NullSpaceSolver::form_reduced(const Eigen::SparseMatrix<double>& jacobian) {
  // K = L' (J C), one column at a time: J C's column in a dense accumulator,
  // then L' of it into K's column.
  const int* j_outer = jacobian.outerIndexPtr();
  const int* j_inner = jacobian.innerIndexPtr();
  const double* j_value = jacobian.valuePtr();
  const int* k_outer = reduced_.outerIndexPtr();
  const int* k_inner = reduced_.innerIndexPtr();
  double* k_value = reduced_.valuePtr();
  std::fill(k_value, k_value + reduced_.nonZeros(), 0.0);
  for (int col = 0; col < reduced_size(); ++col) {
    for (int k = k_outer[col]; k < k_outer[col + 1]; ++k)
      slot_[k_inner[k]] = k;
    touched_.clear();
    for (Eigen::SparseMatrix<double>::InnerIterator c(curl_, col); c; ++c)
      for (int k = j_outer[c.row()]; k < j_outer[c.row() + 1]; ++k) {
        const int row = j_inner[k];
        if (!in_column_[row]) {
          in_column_[row] = 1;
          touched_.push_back(row);
        }
        jc_[row] += j_value[k] * c.value();
      }
    for (const int row : touched_) {
      for (Eigen::SparseMatrix<double>::InnerIterator l(left_, row); l; ++l)
        k_value[slot_[l.row()]] += l.value() * jc_[row];
      jc_[row] = 0.0;
      in_column_[row] = 0;
    }
  }
}

bool NullSpaceSolver::factorize_single(const Eigen::SparseMatrix<double>& jacobian) {
  if (analysed_nonzeros_ < 0) {
    build_reduced_pattern(jacobian);
    single_->analyze(reduced_);
    analysed_nonzeros_ = reduced_.nonZeros();
  }
  form_reduced(jacobian);
  return single_->factorize(reduced_);
}

bool NullSpaceSolver::factorize(const Eigen::SparseMatrix<double>& jacobian) {
  if (single_) return factorize_single(jacobian);
  reduced_ = left_ * (jacobian * curl_);
  // The product keeps explicit zeros, so K's pattern is J's pattern's and
  // never changes; the check only guards the reuse of the symbolic analysis.
  if (reduced_.nonZeros() != analysed_nonzeros_) {
    lu_.control(UMFPACK_IRSTEP) = 0;
    lu_.control(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
    lu_.analyze(reduced_);
    analysed_nonzeros_ = reduced_.nonZeros();
  }
  return lu_.factorize(reduced_);
}

void NullSpaceSolver::solve(const Eigen::SparseMatrix<double>& jacobian, const double* b,
                            double* x) {
  const int* outer = jacobian.outerIndexPtr();
  const int* inner = jacobian.innerIndexPtr();
  const double* value = jacobian.valuePtr();
  du_.assign(n_, 0.0);
  // Momentum rows of J du, for du on the velocity columns.
  auto momentum_of = [&](const std::vector<double>& du, std::vector<double>& out) {
    out.assign(n_, 0.0);
    for (int col = 0; col < n_mom_; ++col) {
      const double d = du[col];
      if (d == 0.0) continue;
      for (int k = outer[col]; k < outer[col + 1]; ++k)
        out[inner[k]] += value[k] * d;
    }
  };
  // A particular velocity that satisfies the continuity rows, carried by
  // the tree faces, leaves first.
  for (auto t = tree_.rbegin(); t != tree_.rend(); ++t) {
    if (t->face < 0) continue;
    const ContinuityRow& row = continuity_[t->p - n_mom_];
    double rest = b[t->p];
    for (int e = 0; e < row.count; ++e)
      if (row.col[e] != t->face) rest -= row.coef[e] * du_[row.col[e]];
    du_[t->face] = rest / t->d_face;
  }
  // The divergence-free part from the reduced system.
  momentum_of(du_, t_);
  r_.assign(n_, 0.0);
  for (int row = 0; row < n_mom_; ++row)
    r_[row] = b[row] - t_[row];
  rz_.resize(curl_.cols());
  z_.resize(curl_.cols());
  Eigen::Map<Eigen::VectorXd>(rz_.data(), rz_.size()) =
      left_ * Eigen::Map<const Eigen::VectorXd>(r_.data(), n_);
  if (single_)
    single_->solve(rz_.data(), z_.data());
  else
    lu_.solve(reduced_, rz_.data(), z_.data());
  Eigen::Map<Eigen::VectorXd>(du_.data(), n_) +=
      curl_ * Eigen::Map<const Eigen::VectorXd>(z_.data(), z_.size());
  // The pressure from the tree faces' momentum rows, roots first.
  momentum_of(du_, t_);
  for (int k = 0; k < n_mom_; ++k)
    x[k] = du_[k];
  for (const TreeCell& t : tree_) {
    if (t.face < 0) {
      x[t.p] = b[t.p] / t.g_own;
      continue;
    }
    double rest = b[t.face] - t_[t.face];
    if (t.parent >= 0) rest -= t.g_parent * x[t.parent];
    x[t.p] = rest / t.g_own;
  }
}

}  // namespace plumekit::cfd
