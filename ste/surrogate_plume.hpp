#pragma once
// The surrogate plume model: the CNN (surrogate/plume_network.hpp) over the
// source position, tabulated. At construction every allowed table cell's
// predicted mean and std plumes (the model's grid) are computed, in batches
// split across threads, so that during a run readings_at(p) is a few bilinear
// lookups per candidate and no network runs inside the loop. On large maps the
// table is coarser than the candidate sources (table_cell > source_cell): a
// candidate then reads the plumes of the table cells around it, each shifted
// by the offset from that cell to the candidate and blended bilinearly (a
// plume moves with its source over a fraction of a metre; docs/validation.md,
// "Candidates finer than the table"). The table can be cached on disk,
// keyed by the SHA-256 of the map's geometry, of the model file and of the
// table grid, and carries a SHA-256 of its own bytes: a damaged or stale
// file is rebuilt (with a note), never trusted. The release rate is a scale
// factor on the table (parameter release_scale), fixed or marginalised by the
// grid estimator.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "cfd/wind_field.hpp"
#include "core/thread_pool.hpp"
#include "ste/forward_model.hpp"

namespace plumekit::surrogate {
class PlumeNetwork;
}

namespace plumekit::ste {

struct SurrogatePlumeOptions {
  std::filesystem::path model;  // plumekit-cnn file
  double source_cell = 0.2;     // m: 50 x 20 candidate sources on the 10 x 4 arena
  // m: the cell of the table the network fills (one plume per allowed cell); 0: source_cell.
  // At least source_cell; coarser keeps the table's build time and memory bounded on large maps.
  double table_cell = 0.0;
  int threads = kDefaultThreads;  // for the table build; 0: one per core
  int batch = 32;
  // Empty: no disk cache. Created if missing; it must be a writable folder, checked before the
  // table is built. Only files named surrogate-table-*.bin (and their temporaries) are written.
  std::filesystem::path cache_dir;
  double scale_lo = 1.0, scale_hi = 1.0;
  // The map's steady wind, for a model that takes it (a physical-grid model); read during
  // construction only. Such a model refuses to build without it.
  const cfd::WindField* wind = nullptr;
  // Told why a cache file was not used and is rebuilt (damaged, stale, older format). Null: a
  // "plumekit: note: ..." line on stderr.
  std::function<void(const std::string&)> on_note;
};

// A table cache file's contents (format in docs/design/ste.md, "Table cache").
struct SurrogateTable {
  std::string key;               // 64 hex digits: map geometry, model file, table grid
  std::uint32_t rows = 0;        // allowed source cells
  std::uint32_t per = 0;         // plume cells of one row (grid ny * nx)
  std::vector<float> mean, std;  // [rows][per] each; finite, >= 0
};

// Parses table cache bytes (`name` names them in messages): magic and version, sizes, the SHA-256
// of the content, finite non-negative values. InputError naming `name` and the fault otherwise.
SurrogateTable parse_table_cache(std::string_view bytes, const std::string& name);
// The bytes parse_table_cache reads back.
std::string table_cache_bytes(const SurrogateTable& table);

class SurrogatePlume final : public SourceTableModel {
 public:
  SurrogatePlume(const Map& map, const SurrogatePlumeOptions& options);
  std::string name() const override { return "surrogate"; }
  const std::vector<Parameter>& parameters() const override { return parameters_; }
  const GridShape& candidates() const override { return candidates_; }
  const std::vector<std::uint8_t>& allowed() const override { return allowed_; }
  std::vector<double> readings_at(Vec2 p) const override;
  // False for a mean-only model (a DeepCFD network of one output; docs/design/surrogate.md).
  bool has_spreads() const override { return has_spreads_; }
  std::vector<double> spreads_at(Vec2 p) const override;

  bool from_cache() const { return from_cache_; }
  // Why an existing cache file was rebuilt; empty when it was used or there was none.
  const std::string& cache_rebuilt_because() const { return rebuilt_because_; }
  const std::filesystem::path& cache_file() const { return cache_file_; }  // empty: no cache
  const std::string& key() const { return key_; }                          // the cache key (hex)
  const GridShape& plume_grid() const { return grid_; }
  const GridShape& table_grid() const { return table_grid_; }
  std::size_t table_rows() const { return rows_; }

 private:
  Map map_;
  std::vector<Parameter> parameters_;
  GridShape candidates_, grid_, table_grid_;
  std::vector<std::uint8_t> allowed_;
  std::size_t rows_ = 0;
  std::vector<int> row_;  // table cell -> row of table_, or -1
  // A candidate's plume is sum_a weight_a * (row_a's plume at p - shift_a). Without a finer
  // candidate grid each candidate has one anchor, its own row unshifted (anchors_ is then unused).
  struct Anchor {
    int row;
    double weight;
    Vec2 shift;  // candidate - table cell centre
  };
  bool shifted_ = false;
  std::vector<std::size_t> first_anchor_;  // per candidate, into anchors_; size candidates + 1
  std::vector<Anchor> anchors_;
  // Ties each candidate to the allowed table cells around it that it sees in a straight line
  // through free candidate cells; a candidate with none is not allowed.
  void anchor_candidates();
  // Per allowed source cell (row), the predicted mean and std plumes: [rows][grid_.ny][grid_.nx].
  std::vector<float> table_, table_std_;
  bool has_spreads_ = true;
  using Note = std::function<void(const std::string&)>;
  // Reads the table from cache_file_ if it is there and this table's; else says why (`note`).
  bool load_cache(std::size_t rows, const Note& note);
  void build_table(const surrogate::PlumeNetwork& plume, const std::vector<Vec2>& cells, int batch);
  // A write that fails is a note: the built table is used uncached.
  void save_cache(std::size_t rows, const Note& note) const;
  // Bilinear values at p of every cell's plume in `table`.
  std::vector<double> lookup(const std::vector<float>& table, Vec2 p) const;
  std::string key_;
  bool from_cache_ = false;
  std::string rebuilt_because_;
  std::filesystem::path cache_file_;
};

}  // namespace plumekit::ste
