#include "cfd/navier_stokes.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "cfd/dual.hpp"

namespace plumekit::cfd {

namespace {

// Lists the distinct unknowns the refs read, in order of first use, and
// gives each ref its slot in that list.
// cols holds kMaxLocal entries, count of them in use.
template <class Term, std::size_t N>
void assign_slots(Term* (&refs)[N], int* cols, int& count) {
  for (Term* r : refs) {
    if (r->col < 0) continue;
    int k = 0;
    while (k < count && cols[k] != r->col)
      ++k;
    if (k == count) {
      if (count == kMaxLocal)
        throw std::logic_error("flow equations: a row depends on more unknowns than kMaxLocal");
      cols[count++] = r->col;
    }
    r->local = k;
  }
}

}  // namespace

NavierStokes::NavierStokes(const StaggeredGrid& grid, Convection convection)
    : grid_(grid), convection_(convection) {
  momentum_.reserve(grid.velocity_unknowns());
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < grid.n_across(c); ++b)
      for (int a = 0; a <= grid.n_along(c); ++a)
        if (grid.kind(c, grid.face(c, a, b)) != kFixed) momentum_.push_back(momentum_row(c, a, b));
  add_continuity_rows();
  build_pattern();
  nu_cell_.assign(grid.shape().size(), 0.0);
  nu_corner_.assign(static_cast<std::size_t>(grid.nx() + 1) * (grid.ny() + 1), 0.0);
}

template <class T>
T NavierStokes::load(const Term& t, const double* x) const {
  const Coef& c = coefs_[t.coef];
  const double v = t.col >= 0 ? c.scale * x[t.col] + c.offset : c.offset;
  if constexpr (std::is_same_v<T, double>) {
    return v;
  } else {
    Dual d(v);
    if (t.col >= 0) d.d[t.local] = c.scale;
    return d;
  }
}

NavierStokes::Term NavierStokes::term(const Ref& r) {
  std::uint64_t bits[2];
  std::memcpy(&bits[0], &r.scale, sizeof(double));
  std::memcpy(&bits[1], &r.offset, sizeof(double));
  const auto [at, added] =
      coef_index_.try_emplace({bits[0], bits[1]}, static_cast<std::uint32_t>(coefs_.size()));
  if (added) {
    if (coefs_.size() >= (1u << 24))
      throw std::logic_error("flow equations: more than 2^24 distinct boundary values");
    coefs_.push_back({r.scale, r.offset});
  }
  Term t;
  t.col = r.col;
  t.coef = at->second;
  t.local = 0;
  return t;
}

NavierStokes::MomentumRow NavierStokes::momentum_row(int c, int a, int b) {
  const StaggeredGrid& grid = grid_;
  const std::size_t f = grid.face(c, a, b);
  MomentumRow m;
  m.row = grid.column(c, f);
  for (int k = -2; k <= 2; ++k)
    m.w[k + 2] = term(k == 0 ? grid.real_face(c, f) : grid.along(c, a, b, k));
  m.wb[1] = term(grid.across(c, a, b, -1));
  m.wb[2] = term(grid.across(c, a, b, 1));
  // Only the limited scheme reads two faces upwind; the others keep a
  // compact stencil, which makes the factorization cheaper.
  const bool wide = convection_ == Convection::VanLeer;
  m.wb[0] = wide ? term(grid.across(c, a, b, -2)) : m.wb[1];
  m.wb[3] = wide ? term(grid.across(c, a, b, 2)) : m.wb[2];
  if (!wide) {
    m.w[0] = m.w[1];
    m.w[4] = m.w[3];
  }
  // The cells a-1 and a beside the face; beyond an outflow face (outside the
  // domain, or an obstacle behind an outlet on its edge) the fluid cell
  // stands in for the missing one: zero gradient.
  int low = a - 1, high = a;
  if (const int side = grid.fluid_side(c, a, b); side == 1)
    low = a;
  else if (side == -1)
    high = a - 1;
  // The other component's faces at the CV's north (b+1) and south (b)
  // sides, in the cells beside it.
  m.o[0] = term(grid.other(c, b + 1, low));
  m.o[1] = term(grid.other(c, b + 1, high));
  m.o[2] = term(grid.other(c, b, low));
  m.o[3] = term(grid.other(c, b, high));
  m.p[0] = term(grid.pressure(c, a, b, false));
  m.p[1] = term(grid.pressure(c, a, b, true));
  m.cell_w = static_cast<int>(grid.cell(c, low, b));
  m.cell_e = static_cast<int>(grid.cell(c, high, b));
  // Corners of the cell grid, (nx+1) x (ny+1), at along a, across b / b+1.
  auto corner = [&](int along, int across) {
    const int i = c == 0 ? along : across, j = c == 0 ? across : along;
    return j * (grid.nx() + 1) + i;
  };
  m.corner_s = corner(a, b);
  m.corner_n = corner(a, b + 1);
  m.inv_ha = 1.0 / grid.h_along(c);
  m.inv_hb = 1.0 / grid.h_across(c);
  return m;
}

void NavierStokes::add_continuity_rows() {
  const StaggeredGrid& grid = grid_;
  continuity_.reserve(grid.unknowns() - grid.velocity_unknowns());
  bool pinned = false;
  for (int j = 0; j < grid.ny(); ++j) {
    for (int i = 0; i < grid.nx(); ++i) {
      const std::size_t cell = grid.shape().index(i, j);
      if (grid.solid(cell)) continue;
      ContinuityRow r;
      r.row = grid.pressure_column(cell);
      r.f[0] = term(grid.real_face(0, grid.face(0, i + 1, j)));
      r.f[1] = term(grid.real_face(0, grid.face(0, i, j)));
      r.f[2] = term(grid.real_face(1, grid.face(1, j + 1, i)));
      r.f[3] = term(grid.real_face(1, grid.face(1, j, i)));
      r.inv_dx = 1.0 / grid.shape().dx();
      r.inv_dy = 1.0 / grid.shape().dy();
      r.pinned = !grid.has_outflow() && !pinned;
      pinned = pinned || r.pinned;
      if (r.pinned) r.f[0] = term(Ref{r.row, 1.0, 0.0, -1});
      continuity_.push_back(r);
    }
  }
}

void NavierStokes::build_pattern() {
  const int n = grid_.unknowns();
  // Row r's distinct unknowns: cols_of_row[r * kMaxLocal + k], k < count_of_row[r].
  std::vector<int> cols_of_row(static_cast<std::size_t>(n) * kMaxLocal), count_of_row(n, 0);
  for (MomentumRow& m : momentum_) {
    Term* refs[] = {&m.w[0],  &m.w[1], &m.w[2], &m.w[3], &m.w[4], &m.wb[0], &m.wb[1], &m.wb[2],
                    &m.wb[3], &m.o[0], &m.o[1], &m.o[2], &m.o[3], &m.p[0],  &m.p[1]};
    assign_slots(refs, &cols_of_row[static_cast<std::size_t>(m.row) * kMaxLocal],
                 count_of_row[m.row]);
  }
  for (ContinuityRow& r : continuity_) {
    Term* refs[] = {&r.f[0], &r.f[1], &r.f[2], &r.f[3]};
    assign_slots(refs, &cols_of_row[static_cast<std::size_t>(r.row) * kMaxLocal],
                 count_of_row[r.row]);
  }
  // The compressed-column pattern, built directly: count the entries of each
  // column, then place rows in increasing order, which keeps every column's
  // row indices sorted. Each (row, slot) remembers where its value lives.
  slot_begin_.assign(n + 1, 0);
  for (int row = 0; row < n; ++row)
    slot_begin_[row + 1] = slot_begin_[row] + count_of_row[row];
  const int nnz = slot_begin_[n];
  slot_value_.resize(nnz);
  std::vector<int> col_start(n + 1, 0);
  for (int row = 0; row < n; ++row)
    for (int k = 0; k < count_of_row[row]; ++k)
      ++col_start[cols_of_row[static_cast<std::size_t>(row) * kMaxLocal + k] + 1];
  for (int col = 0; col < n; ++col)
    col_start[col + 1] += col_start[col];
  jacobian_.resize(n, n);
  jacobian_.resizeNonZeros(nnz);
  std::copy(col_start.begin(), col_start.end(), jacobian_.outerIndexPtr());
  std::vector<int> next(col_start.begin(), col_start.end() - 1);
  for (int row = 0; row < n; ++row)
    for (int k = 0; k < count_of_row[row]; ++k) {
      const int col = cols_of_row[static_cast<std::size_t>(row) * kMaxLocal + k];
      const int at = next[col]++;
      jacobian_.innerIndexPtr()[at] = row;
      jacobian_.valuePtr()[at] = 1.0;
      slot_value_[slot_begin_[row] + k] = at;
    }
}

void NavierStokes::set_viscosity(const std::vector<double>& nu_cell) {
  const int nx = grid_.nx(), ny = grid_.ny();
  nu_cell_ = nu_cell;
  // A corner takes the mean over the fluid cells around it.
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      double sum = 0.0, any = 0.0;
      int n = 0;
      for (int dj = -1; dj <= 0; ++dj)
        for (int di = -1; di <= 0; ++di) {
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
          const std::size_t cell = grid_.shape().index(a, b);
          any = nu_cell[cell];
          if (grid_.solid(cell)) continue;
          sum += nu_cell[cell];
          ++n;
        }
      nu_corner_[static_cast<std::size_t>(j) * (nx + 1) + i] = n ? sum / n : any;
    }
  }
}

template <class T>
T NavierStokes::face_value(const T& flux, const T& far_m, const T& m, const T& p,
                           const T& far_p) const {
  // Value at the face between m and p, carried by `flux` (> 0 from m to p).
  const bool forward = value(flux) >= 0.0;
  switch (convection_) {
    case Convection::Central:
      return 0.5 * (m + p);
    case Convection::Upwind:
      return forward ? m : p;
    case Convection::VanLeer: {
      // Upwind value plus half the van Leer-limited slope:
      // psi(r) (d - u) = (a|b| + |a| b) / (|a| + |b|), a = u - uu, b = d - u.
      const T& up = forward ? m : p;
      const T& down = forward ? p : m;
      const T& far = forward ? far_m : far_p;
      const T a = up - far, b = down - up;
      const T aa = abs(a), ab = abs(b);
      return up + 0.5 * (a * ab + aa * b) / (aa + ab + 1e-30);
    }
  }
  return m;
}

template <class T>
T NavierStokes::momentum(const MomentumRow& r, const double* x) const {
  T w[5], wb[4], o[4];
  for (int k = 0; k < 5; ++k)
    w[k] = load<T>(r.w[k], x);
  for (int k = 0; k < 4; ++k)
    wb[k] = load<T>(r.wb[k], x);
  for (int k = 0; k < 4; ++k)
    o[k] = load<T>(r.o[k], x);
  const T& w0 = w[2];
  const T f_e = 0.5 * (w0 + w[3]), f_w = 0.5 * (w[1] + w0);
  const T g_n = 0.5 * (o[0] + o[1]), g_s = 0.5 * (o[2] + o[3]);
  const T convection =
      (f_e * face_value(f_e, w[1], w0, w[3], w[4]) - f_w * face_value(f_w, w[0], w[1], w0, w[3])) *
          r.inv_ha +
      (g_n * face_value(g_n, wb[1], w0, wb[2], wb[3]) -
       g_s * face_value(g_s, wb[0], wb[1], w0, wb[2])) *
          r.inv_hb;
  const double nu_e = nu_cell_[r.cell_e], nu_w = nu_cell_[r.cell_w];
  const double nu_n = nu_corner_[r.corner_n], nu_s = nu_corner_[r.corner_s];
  const T diffusion = (nu_e * (w[3] - w0) - nu_w * (w0 - w[1])) * (r.inv_ha * r.inv_ha) +
                      (nu_n * (wb[2] - w0) - nu_s * (w0 - wb[1])) * (r.inv_hb * r.inv_hb);
  const T pressure = (load<T>(r.p[1], x) - load<T>(r.p[0], x)) * r.inv_ha;
  return convection - diffusion + pressure;
}

template <class T>
T NavierStokes::continuity(const ContinuityRow& r, const double* x) const {
  if (r.pinned) return load<T>(r.f[0], x);
  return (load<T>(r.f[0], x) - load<T>(r.f[1], x)) * r.inv_dx +
         (load<T>(r.f[2], x) - load<T>(r.f[3], x)) * r.inv_dy;
}

void NavierStokes::residual(const double* x, double* out) const {
  for (const MomentumRow& r : momentum_)
    out[r.row] = momentum<double>(r, x);
  for (const ContinuityRow& r : continuity_)
    out[r.row] = continuity<double>(r, x);
}

void NavierStokes::update_jacobian(const double* x) {
  double* values = jacobian_.valuePtr();
  auto store = [&](int row, const Dual& d) {
    for (int s = slot_begin_[row]; s < slot_begin_[row + 1]; ++s)
      values[slot_value_[s]] = d.d[s - slot_begin_[row]];
  };
  for (const MomentumRow& r : momentum_)
    store(r.row, momentum<Dual>(r, x));
  for (const ContinuityRow& r : continuity_)
    store(r.row, continuity<Dual>(r, x));
}

void NavierStokes::add_to_momentum_diagonal(double s) {
  double* values = jacobian_.valuePtr();
  for (const MomentumRow& r : momentum_)
    values[slot_value_[slot_begin_[r.row] + r.w[2].local]] += s;
}

Eigen::SparseMatrix<double> NavierStokes::continuity_matrix() const {
  const int n_mom = momentum_rows();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(4 * continuity_.size());
  for (const ContinuityRow& r : continuity_) {
    if (r.pinned) continue;
    const double sign[4] = {r.inv_dx, -r.inv_dx, r.inv_dy, -r.inv_dy};
    for (int k = 0; k < 4; ++k)
      if (r.f[k].col >= 0)
        entries.emplace_back(r.row - n_mom, r.f[k].col, sign[k] * coefs_[r.f[k].coef].scale);
  }
  Eigen::SparseMatrix<double> d(size() - n_mom, n_mom);
  d.setFromTriplets(entries.begin(), entries.end());
  return d;
}

}  // namespace plumekit::cfd
