#include "ste/surrogate_plume.hpp"

#include <cstring>
#include <memory>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/map_json.hpp"
#include "core/sha256.hpp"
#include "surrogate/network.hpp"
#include "surrogate/plume_model.hpp"

namespace plumekit::ste {

namespace fs = std::filesystem;

namespace {

// Version 2 holds the std plumes after the mean plumes.
constexpr char kMagic[8] = {'P', 'K', 'S', 'T', 'B', 'L', '2', '\n'};

// The map's geometry (not its name or ground-truth sources, which do not change a plume).
std::string geometry_text(const Map& map) {
  Map m = map;
  m.name.clear();
  m.sources.clear();
  return map_to_json(m).dump();
}

}  // namespace

SurrogatePlume::SurrogatePlume(const Map& map, const SurrogatePlumeOptions& o)
    : map_(map),
      parameters_{
          {"x", 0.0, map.width}, {"y", 0.0, map.height}, {"release_scale", o.scale_lo, o.scale_hi}},
      sources_(GridShape::with_cell(map.width, map.height, o.source_cell)),
      allowed_(free_cells(map, sources_, 0.0)) {
  if (!(o.source_cell > 0.0))
    throw InputError("surrogate plume model: source_cell must be positive");
  if (o.threads < 1 || o.batch < 1)
    throw InputError("surrogate plume model: threads and batch >= 1");
  std::vector<Vec2> cells;
  row_.assign(sources_.size(), -1);
  for (int j = 0; j < sources_.ny; ++j)
    for (int i = 0; i < sources_.nx; ++i)
      if (allowed_[sources_.index(i, j)]) {
        row_[sources_.index(i, j)] = static_cast<int>(cells.size());
        cells.push_back(sources_.centre(i, j));
      }

  surrogate::EngineOptions eo;
  eo.threads = o.threads;
  auto network = std::make_shared<const surrogate::Network>(surrogate::Network::load(o.model, eo));
  const surrogate::PlumeModel plume(network, map);  // checks the model's contract against the map
  grid_ = plume.grid();
  const std::size_t per = grid_.size();

  Sha256 h;
  h.update("plumekit-surrogate-table/2\n");
  h.update(sha256_hex(geometry_text(map)) + "\n" + sha256_file(o.model) + "\n");
  std::ostringstream g;
  g.precision(17);
  g << sources_.nx << ' ' << sources_.ny << ' ' << sources_.width << ' ' << sources_.height;
  h.update(g.str());
  key_ = h.hex_digest();

  const fs::path file = o.cache_dir.empty()
                            ? fs::path()
                            : o.cache_dir / ("surrogate-table-" + key_.substr(0, 16) + ".bin");
  const std::size_t floats = cells.size() * per;  // of each table
  const std::size_t header = sizeof(kMagic) + 64;
  if (!file.empty() && fs::exists(file)) {
    const std::string bytes = read_file(file);
    if (bytes.size() == header + 2 * floats * sizeof(float) &&
        std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) == 0 &&
        bytes.compare(sizeof(kMagic), 64, key_) == 0) {
      table_.resize(floats);
      table_std_.resize(floats);
      std::memcpy(table_.data(), bytes.data() + header, floats * sizeof(float));
      std::memcpy(table_std_.data(), bytes.data() + header + floats * sizeof(float),
                  floats * sizeof(float));
      from_cache_ = true;
      return;
    }
    // A stale or damaged file is rebuilt and replaced below.
  }
  table_.resize(floats);
  table_std_.resize(floats);
  for (std::size_t first = 0; first < cells.size(); first += 256) {
    const std::vector<Vec2> chunk(cells.begin() + first,
                                  cells.begin() + std::min(cells.size(), first + 256));
    const std::vector<surrogate::PlumePrediction> p = plume.predict_batch(chunk, o.batch);
    for (std::size_t k = 0; k < p.size(); ++k) {
      std::memcpy(table_.data() + (first + k) * per, p[k].mean.data(), per * sizeof(float));
      std::memcpy(table_std_.data() + (first + k) * per, p[k].std.data(), per * sizeof(float));
    }
  }
  if (!file.empty()) {
    fs::create_directories(o.cache_dir);
    std::string bytes(kMagic, sizeof(kMagic));
    bytes += key_;
    bytes.append(reinterpret_cast<const char*>(table_.data()), floats * sizeof(float));
    bytes.append(reinterpret_cast<const char*>(table_std_.data()), floats * sizeof(float));
    write_file_atomic(file, bytes);
  }
}

std::vector<double> SurrogatePlume::readings_at(Vec2 p) const {
  return lookup(table_, p);
}

std::vector<double> SurrogatePlume::spreads_at(Vec2 p) const {
  return lookup(table_std_, p);
}

std::vector<double> SurrogatePlume::lookup(const std::vector<float>& table, Vec2 p) const {
  std::vector<double> out(sources_.size(), 0.0);
  if (!map_.is_free(p)) return out;  // the surrogate predicts 0 inside obstacles
  const GridShape::Bilinear b = grid_.bilinear(p);
  const std::size_t per = grid_.size();
  const std::size_t k00 = grid_.index(b.i0, b.j0), k10 = grid_.index(b.i1, b.j0),
                    k01 = grid_.index(b.i0, b.j1), k11 = grid_.index(b.i1, b.j1);
  const double w00 = (1 - b.tx) * (1 - b.ty), w10 = b.tx * (1 - b.ty), w01 = (1 - b.tx) * b.ty,
               w11 = b.tx * b.ty;
  for (std::size_t c = 0; c < out.size(); ++c) {
    if (row_[c] < 0) continue;
    const float* t = table.data() + static_cast<std::size_t>(row_[c]) * per;
    out[c] = w00 * t[k00] + w10 * t[k10] + w01 * t[k01] + w11 * t[k11];
  }
  return out;
}

}  // namespace plumekit::ste
