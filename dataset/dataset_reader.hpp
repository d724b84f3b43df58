#pragma once
// The one reader of a dataset's own files: manifest.json (and its parts),
// parameters.json and each shard's checksums.json and arrays. Everything is
// validated before use; a fault throws InputError naming the file, the key and
// the fault, and says what to do, so `dataset show`, `dataset merge` and a
// resumed `dataset generate` never act on a damaged file.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/geometry.hpp"
#include "core/grid.hpp"
#include "dataset/shard.hpp"
#include "map/map.hpp"

namespace plumekit::dataset {

struct ManifestShard {
  std::string name;  // shard-00007 (always shard_name(map_index))
  int map_index = 0;
  std::string map;  // maps/map-00007.json (always that form)
  std::string family;
  int samples = 0;
  Checksums sha256;  // exactly the files of kShardFiles
};

struct Manifest {
  nlohmann::ordered_json generator;  // the parameters (parameters.json's content)
  int maps = 0;                      // generator.maps
  int part_k = 0, part_n = 1;        // part_n 1: a whole dataset, every map once
  long long samples = 0;             // the sum over the shards
  std::vector<ManifestShard> shards;
};

// manifest.json or manifest.part-K-of-N.json from its bytes (`name` names them in messages).
Manifest parse_manifest(std::string_view bytes, const std::string& name);
Manifest read_manifest(const std::filesystem::path& file);
// Every manifest.part-K-of-N.json of a `dataset generate --shard K/N` folder, by file name;
// InputError when `dir` is not a folder or holds none.
std::vector<Manifest> read_part_manifests(const std::filesystem::path& dir);

// parameters.json: a JSON object with at least "seed" and "maps".
nlohmann::ordered_json parse_parameters(std::string_view bytes, const std::string& name);
nlohmann::ordered_json read_parameters(const std::filesystem::path& file);

// One line per parameter that differs, by its dotted key and both values:
// `filament.release_rate: this run 1000.0, the dataset 500.0`.
std::vector<std::string> parameter_differences(const nlohmann::json& this_run,
                                               const nlohmann::json& dataset);

// A shard's checksums.json: exactly the files of kShardFiles, each a 64-digit SHA-256.
Checksums parse_checksums(std::string_view bytes, const std::string& name);

// Checks a shard folder: its checksums.json against its files and, when `expected` is not empty,
// against the manifest's checksums. InputError naming the first file that does not match.
void check_shard(const std::filesystem::path& dir, const Checksums& expected);

// The samples a shard's files hold: the first dimension of each array of kShardFiles, read from
// their headers. InputError naming the file when one is not a whole array or the files disagree.
long long shard_samples(const std::filesystem::path& dir);

// The dataset's feature cell (generator.feature_cell; 0 for the thesis's 64 x 64 grid).
double feature_cell(const Manifest& m);
// Whether the dataset's inputs hold the physics_mean channel (generator.physics_input; 6
// channels).
bool physics_input(const Manifest& m);

// The checked arrays of `entry` in the dataset `dataset_dir` (map_ids left empty: they equal
// entry.map_index, which the checksum covers): shapes as manifest.json's contract says, `channels`
// input channels (input_channels(feature_cell(manifest), physics_input(manifest))); the grid is the
// shard's own (its map's).
ShardArrays read_shard(const std::filesystem::path& dataset_dir, const ManifestShard& entry,
                       int channels);

// One sample of a dataset, by its index over the whole dataset (shards in manifest order), with
// the map it was made on: what `dataset show` draws and what the trainer's reader must agree with.
struct DatasetSample {
  long long index = 0;
  ManifestShard shard;  // the shard that holds it
  int row = 0;          // its row in that shard
  Map map;              // the shard's map file
  Vec2 source;
  // On the map's feature grid (row 0 at y = 0), channels as manifest.json's contract says.
  std::vector<Grid<double>> inputs;   // region label, signed distance, [wind u, v,] source distance
  std::vector<Grid<double>> targets;  // mean, std
  // SHA-256 of the sample's raw float32 rows as stored (inputs [3,64,64], targets [2,64,64]):
  // what another reader of the same files must reproduce bit for bit.
  std::string inputs_sha256, targets_sha256;
};

// Reads sample `index` of the dataset in `dir` through the checked manifest and shard;
// OptionError naming "show.index" when the dataset has no such sample.
DatasetSample read_sample(const std::filesystem::path& dir, long long index);

}  // namespace plumekit::dataset
