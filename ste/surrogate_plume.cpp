#include "ste/surrogate_plume.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/memory_limit.hpp"
#include "core/sha256.hpp"
#include "core/thread_pool.hpp"
#include "map/map_json.hpp"
#include "surrogate/network.hpp"
#include "surrogate/plume_network.hpp"

namespace plumekit::ste {

namespace fs = std::filesystem;

namespace {

// Version 3: a key, the table's sizes, the mean then the std plumes, and a SHA-256 of all of it.
constexpr char kMagic[8] = {'P', 'K', 'S', 'T', 'B', 'L', '3', '\n'};
constexpr std::size_t kKeyChars = 64;
constexpr std::size_t kHeader = sizeof(kMagic) + kKeyChars + 8;  // + rows, per (u32 each)
constexpr std::size_t kDigest = 32;

// The map's geometry (not its name or ground-truth sources, which do not change a plume).
std::string geometry_text(const Map& map) {
  Map m = map;
  m.name.clear();
  m.sources.clear();
  return map_to_json(m).dump();
}

std::uint32_t read_u32_le(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t{b[0]} | (std::uint32_t{b[1]} << 8) | (std::uint32_t{b[2]} << 16) |
         (std::uint32_t{b[3]} << 24);
}

void append_u32_le(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}

bool is_lower_hex(std::string_view s) {
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// Reads `count` floats at `p`, each finite and >= 0 (the model clamps negative plumes to 0).
std::vector<float> read_plumes(const char* p, std::size_t count, const char* which,
                               std::uint32_t per, const std::string& name) {
  std::vector<float> v(count);
  if (count > 0) std::memcpy(v.data(), p, count * sizeof(float));  // data() may be null when empty
  for (std::size_t k = 0; k < count; ++k)
    if (!std::isfinite(v[k]) || v[k] < 0.0f) {
      std::ostringstream os;
      os << name << ": " << which << " plume " << k / per << " cell " << k % per << " holds "
         << v[k] << ", not a finite concentration >= 0 (the file is damaged)";
      throw InputError(os.str());
    }
  return v;
}

// Before the (long) table build: the cache folder exists or is made, and a file can be written
// in it. Only a file of the cache's own name (and its probe) is ever created there.
void prepare_cache_dir(const fs::path& dir, const fs::path& file) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st) && !fs::is_directory(st))
    throw InputError("table cache " + dir.string() +
                     ": exists and is not a folder; name a folder for the surrogate tables (it is "
                     "created if missing)");
  if (!fs::exists(st)) {
    fs::create_directories(dir, ec);
    if (ec)
      throw InputError("table cache " + dir.string() + ": cannot create the folder (" +
                       ec.message() + "); name a folder you can write");
  }
  const fs::file_status fst = fs::symlink_status(file, ec);
  if (fs::exists(fst) && !fs::is_regular_file(fs::status(file, ec)))
    throw InputError("table cache " + file.string() +
                     ": exists and is not a table file; move it away or name another folder");
  const fs::path probe = file.string() + ".probe-" + std::to_string(::getpid());
  bool writable = false;
  {
    std::ofstream out(probe, std::ios::binary | std::ios::trunc);
    out << "probe";
    out.close();
    writable = static_cast<bool>(out);
  }
  fs::remove(probe, ec);
  if (!writable)
    throw InputError("table cache " + dir.string() +
                     ": cannot write in this folder (permission or a full disk?); name a folder "
                     "you can write, or run without a table cache");
}

// The cache key: the map's geometry, the model file, the table grid and the wind.
std::string table_key(const Map& map, const fs::path& model, const GridShape& candidates,
                      const cfd::WindField* wind) {
  Sha256 h;
  h.update("plumekit-surrogate-table/2\n");  // the key's own version; the file's is kMagic
  h.update(sha256_hex(geometry_text(map)) + "\n" + sha256_file(model) + "\n");
  std::ostringstream g;
  g.precision(17);
  g << candidates.nx << ' ' << candidates.ny << ' ' << candidates.width << ' ' << candidates.height;
  h.update(g.str());
  if (wind) {  // a model that reads the wind: another flow is another table
    const auto bytes = [&](const std::vector<double>& v) {
      h.update(
          std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double)));
    };
    h.update("\nwind\n");
    bytes(wind->face_u());
    bytes(wind->face_v());
  }
  return h.hex_digest();
}

// Bilinear interpolation of a plume on `grid` at p, between cell centres: four cells and weights.
struct Taps {
  std::size_t k00, k10, k01, k11;
  double w00, w10, w01, w11;
  Taps(const GridShape& grid, Vec2 p) {
    const GridShape::Bilinear b = grid.bilinear(p);
    k00 = grid.index(b.i0, b.j0), k10 = grid.index(b.i1, b.j0);
    k01 = grid.index(b.i0, b.j1), k11 = grid.index(b.i1, b.j1);
    w00 = (1 - b.tx) * (1 - b.ty), w10 = b.tx * (1 - b.ty), w01 = (1 - b.tx) * b.ty;
    w11 = b.tx * b.ty;
  }
  double operator()(const float* t) const {
    return w00 * t[k00] + w10 * t[k10] + w01 * t[k01] + w11 * t[k11];
  }
};

// How many candidates' (or anchors') table reads a lookup asks the memory for ahead of using them.
constexpr std::size_t kLookahead = 64;

void prefetch_taps(const Taps& taps, const float* t) {
  __builtin_prefetch(t + taps.k00);
  __builtin_prefetch(t + taps.k10);
  __builtin_prefetch(t + taps.k01);
  __builtin_prefetch(t + taps.k11);
}

void print_note(const std::string& note) {
  std::cerr << "plumekit: note: " << note << "\n";
}

}  // namespace

SurrogateTable parse_table_cache(std::string_view bytes, const std::string& name) {
  const auto fail = [&](const std::string& what) { return InputError(name + ": " + what); };
  if (bytes.size() < sizeof(kMagic) || bytes.compare(0, 6, "PKSTBL") != 0)
    throw fail("not a surrogate table cache (wrong magic)");
  if (bytes.compare(0, sizeof(kMagic), std::string_view(kMagic, sizeof(kMagic))) != 0)
    throw fail("an older or unknown table cache format (this plumekit reads PKSTBL3)");
  if (bytes.size() < kHeader + kDigest)
    throw fail("truncated: " + std::to_string(bytes.size()) +
               " bytes, shorter than the header and checksum");
  const std::string_view body = bytes.substr(0, bytes.size() - kDigest);
  const Sha256Digest digest = sha256(body);
  if (bytes.compare(body.size(), kDigest,
                    std::string_view(reinterpret_cast<const char*>(digest.data()), kDigest)) != 0)
    throw fail("checksum mismatch (the file is truncated or damaged)");
  SurrogateTable t;
  t.key = std::string(bytes.substr(sizeof(kMagic), kKeyChars));
  if (!is_lower_hex(t.key)) throw fail("the key is not 64 hex digits");
  t.rows = read_u32_le(bytes.data() + sizeof(kMagic) + kKeyChars);
  t.per = read_u32_le(bytes.data() + sizeof(kMagic) + kKeyChars + 4);
  const std::uint64_t cells = std::uint64_t{t.rows} * t.per;  // < 2^64: both are u32
  const std::uint64_t data = body.size() - kHeader;
  if (t.per == 0 || cells > data / (2 * sizeof(float)) || 2 * sizeof(float) * cells != data)
    throw fail(std::to_string(data) + " bytes of plumes do not hold 2 x " + std::to_string(t.rows) +
               " rows x " + std::to_string(t.per) + " float32 cells");
  const char* p = bytes.data() + kHeader;
  t.mean = read_plumes(p, cells, "mean", t.per, name);
  t.std = read_plumes(p + cells * sizeof(float), cells, "std", t.per, name);
  return t;
}

std::string table_cache_bytes(const SurrogateTable& t) {
  std::string bytes(kMagic, sizeof(kMagic));
  bytes += t.key;
  append_u32_le(bytes, t.rows);
  append_u32_le(bytes, t.per);
  bytes.append(reinterpret_cast<const char*>(t.mean.data()), t.mean.size() * sizeof(float));
  bytes.append(reinterpret_cast<const char*>(t.std.data()), t.std.size() * sizeof(float));
  const Sha256Digest digest = sha256(bytes);
  bytes.append(reinterpret_cast<const char*>(digest.data()), digest.size());
  return bytes;
}

SurrogatePlume::SurrogatePlume(const Map& map, const SurrogatePlumeOptions& o)
    : map_(map),
      parameters_{{"x", 0.0, map.width},
                  {"y", 0.0, map.height},
                  {"release_scale", o.scale_lo, o.scale_hi}} {
  if (!(o.source_cell > 0.0))
    throw InputError("surrogate plume model: source_cell must be positive");
  if (!(o.table_cell == 0.0 || o.table_cell >= o.source_cell))
    throw InputError(
        "surrogate plume model: table_cell must be 0 (the source cell) or at least "
        "source_cell");
  if (o.threads < 0 || o.batch < 1)
    throw InputError("surrogate plume model: threads >= 0 and batch >= 1");
  candidates_ = GridShape::with_cell(map.width, map.height, o.source_cell);
  allowed_ = free_cells(map, candidates_, 0.0);
  table_grid_ =
      o.table_cell > 0.0 ? GridShape::with_cell(map.width, map.height, o.table_cell) : candidates_;
  shifted_ = table_grid_.nx != candidates_.nx || table_grid_.ny != candidates_.ny;
  const std::vector<std::uint8_t> table_allowed =
      shifted_ ? free_cells(map, table_grid_, 0.0) : allowed_;
  std::vector<Vec2> cells;
  row_.assign(table_grid_.size(), -1);
  for (int j = 0; j < table_grid_.ny; ++j)
    for (int i = 0; i < table_grid_.nx; ++i)
      if (table_allowed[table_grid_.index(i, j)]) {
        row_[table_grid_.index(i, j)] = static_cast<int>(cells.size());
        cells.push_back(table_grid_.centre(i, j));
      }
  rows_ = cells.size();
  if (shifted_) anchor_candidates();
  surrogate::EngineOptions eo;
  eo.threads = resolve_threads(o.threads);
  auto network = std::make_shared<const surrogate::Network>(surrogate::Network::load(o.model, eo));
  const cfd::WindField* wind = surrogate::PlumeNetwork::takes_wind(*network) ? o.wind : nullptr;
  // Checks the model's contract against the map (and that a model that reads the wind has one).
  const surrogate::PlumeNetwork plume(network, map, wind);
  grid_ = plume.grid();
  has_spreads_ = plume.has_std();
  // The table: a mean and a std plume per allowed cell, on the model's grid (a physical-grid
  // model's grows with the map).
  check_memory(8.0 * static_cast<double>(cells.size()) * static_cast<double>(grid_.size()),
               "the surrogate table of " + std::to_string(cells.size()) + " table cells x " +
                   std::to_string(grid_.size()) + " plume cells",
               "use a larger ste.table_cell (or ste.source_cell)");
  key_ = table_key(map, o.model, table_grid_, wind);
  cache_file_ = o.cache_dir.empty()
                    ? fs::path()
                    : o.cache_dir / ("surrogate-table-" + key_.substr(0, 16) + ".bin");
  const Note note = [&](const std::string& text) { (o.on_note ? o.on_note : print_note)(text); };
  for (const std::string& w : plume.warnings())  // outside what the model was trained on
    note("surrogate model: " + w);
  if (!cache_file_.empty()) {
    prepare_cache_dir(o.cache_dir, cache_file_);
    if (load_cache(cells.size(), note)) return;
  }
  build_table(plume, cells, o.batch);
  if (!cache_file_.empty()) save_cache(cells.size(), note);
}

bool SurrogatePlume::load_cache(std::size_t rows, const Note& note) {
  if (!fs::exists(cache_file_)) return false;
  try {
    SurrogateTable t = parse_table_cache(read_file(cache_file_), cache_file_.string());
    if (t.key != key_ || t.rows != rows || t.per != grid_.size())
      throw InputError(cache_file_.string() +
                       ": made for another map, model or table grid (its key differs)");
    table_ = std::move(t.mean);
    table_std_ = std::move(t.std);
    from_cache_ = true;
    return true;
  } catch (const InputError& e) {
    rebuilt_because_ = e.what();
    note("table cache " + rebuilt_because_ + "; rebuilding the table");
    return false;
  }
}

void SurrogatePlume::build_table(const surrogate::PlumeNetwork& plume,
                                 const std::vector<Vec2>& cells, int batch) {
  const std::size_t per = grid_.size();
  table_.resize(cells.size() * per);
  table_std_.resize(cells.size() * per);
  for (std::size_t first = 0; first < cells.size(); first += 256) {
    check_interrupt();  // a caller's Ctrl-C (core/interrupt.hpp)
    const std::vector<Vec2> chunk(cells.begin() + first,
                                  cells.begin() + std::min(cells.size(), first + 256));
    const std::vector<surrogate::PlumePrediction> p = plume.predict_batch(chunk, batch);
    for (std::size_t k = 0; k < p.size(); ++k) {
      std::memcpy(table_.data() + (first + k) * per, p[k].mean.data(), per * sizeof(float));
      if (!p[k].std.empty())  // a mean-only model's spreads stay 0 (has_spreads() is false)
        std::memcpy(table_std_.data() + (first + k) * per, p[k].std.data(), per * sizeof(float));
    }
  }
}

void SurrogatePlume::save_cache(std::size_t rows, const Note& note) const {
  SurrogateTable t;
  t.key = key_;
  t.rows = static_cast<std::uint32_t>(rows);
  t.per = static_cast<std::uint32_t>(grid_.size());
  t.mean = table_;
  t.std = table_std_;
  try {
    write_file_atomic(cache_file_, table_cache_bytes(t));
  } catch (const InputError& e) {
    // The table is built and correct: losing only its cache is not worth failing the run.
    note("table cache " + std::string(e.what()) + "; the table is used without being cached");
  }
}

std::vector<double> SurrogatePlume::readings_at(Vec2 p) const {
  return lookup(table_, p);
}

std::vector<double> SurrogatePlume::spreads_at(Vec2 p) const {
  return lookup(table_std_, p);
}

std::vector<double> SurrogatePlume::lookup(const std::vector<float>& table, Vec2 p) const {
  std::vector<double> out(candidates_.size(), 0.0);
  if (!map_.is_free(p)) return out;  // the surrogate predicts 0 inside obstacles
  const auto plume = [&](int row) {
    return table.data() + static_cast<std::size_t>(row) * grid_.size();
  };
  if (!shifted_) {
    const Taps taps(grid_, p);
    const auto touch = [&](std::size_t c) {
      if (row_[c] >= 0) prefetch_taps(taps, plume(row_[c]));
    };
    for (std::size_t c = 0; c < std::min(kLookahead, out.size()); ++c)
      touch(c);
    for (std::size_t c = 0; c < out.size(); ++c) {
      if (c + kLookahead < out.size()) touch(c + kLookahead);
      if (row_[c] >= 0) out[c] = taps(plume(row_[c]));
    }
    return out;
  }
  // Each anchor reads four floats of its own row, a table's size apart: the loads miss the cache,
  // so a chunk's taps are computed and prefetched before they are summed (in the same order, so
  // the sums are the same bytes).
  std::vector<Taps> taps;
  taps.reserve(kLookahead);
  for (std::size_t c0 = 0; c0 < out.size();) {
    std::size_t c1 = c0;
    taps.clear();
    const auto anchors = [&](std::size_t c) { return first_anchor_[c + 1] - first_anchor_[c]; };
    while (c1 < out.size() && (c1 == c0 || taps.size() + anchors(c1) <= kLookahead)) {
      for (std::size_t a = first_anchor_[c1]; a < first_anchor_[c1 + 1]; ++a) {
        taps.emplace_back(grid_, p - anchors_[a].shift);
        prefetch_taps(taps.back(), plume(anchors_[a].row));
      }
      ++c1;
    }
    const Taps* t = taps.data();
    for (std::size_t c = c0; c < c1; ++c)
      for (std::size_t a = first_anchor_[c]; a < first_anchor_[c + 1]; ++a, ++t)
        out[c] += anchors_[a].weight * (*t)(plume(anchors_[a].row));
    c0 = c1;
  }
  return out;
}

void SurrogatePlume::anchor_candidates() {
  // Free in a straight line from a to b: every point along it, at steps of a quarter of the
  // finer cell, lies in an allowed candidate cell (the rasterised free space).
  const double step = 0.25 * std::min(candidates_.dx(), candidates_.dy());
  const auto cell_free = [&](Vec2 q) {
    const int i = std::clamp(static_cast<int>(q.x / candidates_.dx()), 0, candidates_.nx - 1);
    const int j = std::clamp(static_cast<int>(q.y / candidates_.dy()), 0, candidates_.ny - 1);
    return allowed_[candidates_.index(i, j)] != 0;
  };
  const auto sees = [&](Vec2 a, Vec2 b) {
    const int n = static_cast<int>(std::ceil(norm(b - a) / step));
    for (int k = 1; k < n; ++k)
      if (!cell_free(a + (static_cast<double>(k) / n) * (b - a))) return false;
    return true;
  };
  first_anchor_.assign(candidates_.size() + 1, 0);
  for (int j = 0; j < candidates_.ny; ++j)
    for (int i = 0; i < candidates_.nx; ++i) {
      const std::size_t c = candidates_.index(i, j);
      first_anchor_[c] = anchors_.size();
      if (!allowed_[c]) continue;
      const Vec2 s = candidates_.centre(i, j);
      // The four table cells around s, bilinear weights (renormalised over those it may use).
      // (A one-cell axis has t = 0, so its second cell's weight is 0 and skipped.)
      const GridShape::Bilinear b = table_grid_.bilinear(s);
      const int is[2] = {b.i0, b.i1}, js[2] = {b.j0, b.j1};
      const double wx[2] = {1 - b.tx, b.tx}, wy[2] = {1 - b.ty, b.ty};
      double total = 0.0;
      for (int bj = 0; bj < 2; ++bj)
        for (int bi = 0; bi < 2; ++bi) {
          const double w = wx[bi] * wy[bj];
          const int row = row_[table_grid_.index(is[bi], js[bj])];
          const Vec2 centre = table_grid_.centre(is[bi], js[bj]);
          if (w <= 0.0 || row < 0 || !sees(s, centre)) continue;
          anchors_.push_back({row, w, s - centre});
          total += w;
        }
      if (total > 0.0) {
        for (std::size_t a = first_anchor_[c]; a < anchors_.size(); ++a)
          anchors_[a].weight /= total;
        continue;
      }
      // None around it (next to a wall): the nearest allowed table cell it sees, within two
      // table cells.
      const int ci = std::clamp(static_cast<int>(s.x / table_grid_.dx()), 0, table_grid_.nx - 1);
      const int cj = std::clamp(static_cast<int>(s.y / table_grid_.dy()), 0, table_grid_.ny - 1);
      double best = std::numeric_limits<double>::infinity();
      Anchor nearest{-1, 1.0, {}};
      for (int tj = cj - 2; tj <= cj + 2; ++tj)
        for (int ti = ci - 2; ti <= ci + 2; ++ti) {
          if (!table_grid_.contains(ti, tj)) continue;
          const int row = row_[table_grid_.index(ti, tj)];
          const Vec2 centre = table_grid_.centre(ti, tj);
          const double d = norm(s - centre);
          if (row < 0 || d >= best || !sees(s, centre)) continue;
          best = d;
          nearest = {row, 1.0, s - centre};
        }
      if (nearest.row >= 0)
        anchors_.push_back(nearest);
      else
        allowed_[c] = 0;  // no plume to give it: not a candidate
    }
  first_anchor_[candidates_.size()] = anchors_.size();
}

}  // namespace plumekit::ste
