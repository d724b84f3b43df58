#include "cfd/openfoam_fields.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace plumekit::cfd {

namespace fs = std::filesystem;

namespace {

// A cursor over a field file's text.
class Reader {
 public:
  Reader(std::string text, std::string name) : t_(std::move(text)), name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(name_ + ": cannot read OpenFOAM's result (" + what + ")");
  }
  void skip_space() {
    while (pos_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[pos_])))
      ++pos_;
  }
  std::string word() {
    skip_space();
    const std::size_t start = pos_;
    while (pos_ < t_.size() && !std::isspace(static_cast<unsigned char>(t_[pos_])) &&
           t_[pos_] != '(' && t_[pos_] != '{' && t_[pos_] != '}' && t_[pos_] != ';')
      ++pos_;
    return t_.substr(start, pos_ - start);
  }
  void expect(char c) {
    skip_space();
    if (pos_ >= t_.size() || t_[pos_] != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  char peek() {
    skip_space();
    return pos_ < t_.size() ? t_[pos_] : '\0';
  }
  double number() {
    while (pos_ < t_.size() && (std::isspace(static_cast<unsigned char>(t_[pos_])) ||
                                t_[pos_] == '(' || t_[pos_] == ')'))
      ++pos_;
    char* end = nullptr;
    const double v = std::strtod(t_.c_str() + pos_, &end);
    if (end == t_.c_str() + pos_) fail("expected a number");
    pos_ = static_cast<std::size_t>(end - t_.c_str());
    return v;
  }
  // Moves past the keyword `key` standing alone at or after the cursor,
  // not beyond `limit`; false when there is none.
  bool seek(const std::string& key, std::size_t limit = std::string::npos) {
    for (std::size_t at = t_.find(key, pos_); at < limit; at = t_.find(key, at + 1)) {
      const bool starts = at == 0 || std::isspace(static_cast<unsigned char>(t_[at - 1])) ||
                          t_[at - 1] == ';' || t_[at - 1] == '{';
      const std::size_t after = at + key.size();
      if (starts && after < t_.size() && std::isspace(static_cast<unsigned char>(t_[after]))) {
        pos_ = after;
        return true;
      }
    }
    return false;
  }
  // The position one past the '}' closing the block whose '{' was just read.
  std::size_t block_end() const {
    int depth = 1;
    for (std::size_t k = pos_; k < t_.size(); ++k) {
      if (t_[k] == '{') ++depth;
      if (t_[k] == '}' && --depth == 0) return k + 1;
    }
    fail("unbalanced braces");
  }
  std::size_t pos() const { return pos_; }
  void set_pos(std::size_t p) { pos_ = p; }

  // `uniform X`, `uniform (X Y Z)` or `nonuniform List<T> N (...)`.
  FoamValues value(int width) {
    FoamValues v;
    const std::string kind = word();
    if (kind == "uniform") {
      v.uniform = true;
      for (int k = 0; k < width; ++k)
        v.values.push_back(number());
      return v;
    }
    if (kind != "nonuniform") fail("expected uniform or nonuniform");
    word();  // List<scalar> / List<vector>
    skip_space();
    std::size_t n = 0;
    while (pos_ < t_.size() && std::isdigit(static_cast<unsigned char>(t_[pos_])))
      n = n * 10 + static_cast<std::size_t>(t_[pos_++] - '0');
    expect('(');
    v.values.resize(n * width);
    for (double& x : v.values)
      x = number();
    return v;
  }

 private:
  std::string t_, name_;
  std::size_t pos_ = 0;
};

}  // namespace

std::vector<double> FoamValues::expand(std::size_t n, int width, const std::string& what) const {
  if (!uniform) {
    if (values.size() != n * width)
      throw InputError("OpenFOAM's " + what + " has " + std::to_string(values.size() / width) +
                       " values where the mesh has " + std::to_string(n));
    return values;
  }
  std::vector<double> out;
  out.reserve(n * width);
  for (std::size_t k = 0; k < n; ++k)
    out.insert(out.end(), values.begin(), values.end());
  return out;
}

FoamField read_foam_field(const fs::path& file, int width) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": OpenFOAM wrote no such result file");
  std::ostringstream text;
  text << in.rdbuf();
  Reader r(text.str(), file.string());
  FoamField field;
  if (!r.seek("internalField")) r.fail("no internalField");
  field.internal = r.value(width);
  if (!r.seek("boundaryField")) r.fail("no boundaryField");
  r.expect('{');
  while (r.peek() != '}') {
    const std::string name = r.word();
    if (name.empty()) r.fail("expected a patch name");
    r.expect('{');
    const std::size_t end = r.block_end();
    if (r.seek("value", end)) field.patches[name] = r.value(width);
    r.set_pos(end);
  }
  return field;
}

std::string latest_time(const fs::path& dir) {
  std::string best;
  double best_t = 0.0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    char* end = nullptr;
    const double t = std::strtod(name.c_str(), &end);
    if (!e.is_directory() || name.empty() || *end != '\0' || t <= 0.0) continue;
    if (best.empty() || t > best_t) best = name, best_t = t;
  }
  return best;
}

FlowResult wind_from_foam(const StaggeredGrid& grid, const FoamMesh& mesh, const FoamField& phi,
                          const FoamField& p, double nu) {
  const GridShape& s = grid.shape();
  std::vector<double> face[2] = {std::vector<double>(grid.face_count(0), 0.0),
                                 std::vector<double>(grid.face_count(1), 0.0)};
  const double area[2] = {s.dy() * mesh.depth, s.dx() * mesh.depth};
  auto put = [&](int start, const std::vector<double>& flux) {
    for (std::size_t k = 0; k < flux.size(); ++k) {
      const MacFace& m = mesh.mac[start + k];
      face[m.c][m.f] = m.sign * flux[k] / area[m.c];
    }
  };
  put(0, phi.internal.expand(mesh.n_internal(), 1, "phi"));
  FlowSummary summary;
  for (const FoamPatch& patch : mesh.patches) {
    if (patch.type == "empty") continue;
    const auto it = phi.patches.find(patch.name);
    if (it == phi.patches.end()) throw InputError("OpenFOAM's phi has no patch " + patch.name);
    const std::vector<double> flux = it->second.expand(patch.size, 1, "phi on " + patch.name);
    put(patch.start, flux);
    double out = 0.0;  // m^2/s per metre of depth, leaving the domain
    for (double f : flux)
      out += f / mesh.depth;
    if (patch.name == "inlet") summary.inflow = -out;
    if (patch.name == "outlet") summary.outflow = out;
  }
  const std::vector<double> cell_p = p.internal.expand(mesh.cell_of.size(), 1, "p");
  std::vector<double> pressure(s.size(), 0.0);
  for (std::size_t k = 0; k < mesh.cell_of.size(); ++k)
    pressure[mesh.cell_of[k]] = cell_p[k];
  FlowResult r{
      WindField(s, std::move(face[0]), std::move(face[1]), std::move(pressure), grid.solid_cells()),
      summary};
  FlowSummary& sum = r.summary;
  sum.nx = s.nx, sum.ny = s.ny, sum.dx = s.dx(), sum.dy = s.dy(), sum.nu = nu;
  sum.mass_imbalance = sum.inflow > 0.0 ? std::abs(sum.inflow - sum.outflow) / sum.inflow : 0.0;
  sum.max_speed = r.wind.max_speed();
  return r;
}

}  // namespace plumekit::cfd
