// Datasets (dataset/): a `plumekit dataset generate` folder read back whole, every file checked.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "core/error.hpp"
#include "dataset/dataset_reader.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "surrogate/features.hpp"

namespace plumekit::python {

namespace {

// Appends `values` into `out` at `offset` (elements), the arrays being preallocated.
template <class T>
void put(py::array_t<T>& out, std::size_t offset, const std::vector<T>& values) {
  std::copy(values.begin(), values.end(), out.mutable_data() + offset);
}

// A shard's arrays as numpy arrays, shaped as manifest.json's contract says.
py::dict shard_dict(const dataset::ManifestShard& entry, const dataset::ShardArrays& a) {
  const auto n = static_cast<py::ssize_t>(a.samples);
  py::array_t<float> inputs({n, py::ssize_t{a.channels}, py::ssize_t{a.ny}, py::ssize_t{a.nx}});
  py::array_t<float> targets({n, py::ssize_t{2}, py::ssize_t{a.ny}, py::ssize_t{a.nx}});
  py::array_t<float> sources({n, py::ssize_t{2}});
  put(inputs, 0, a.inputs);
  put(targets, 0, a.targets);
  put(sources, 0, a.sources);
  py::dict out;
  out["map_id"] = entry.map_index;
  out["map"] = entry.map;
  out["family"] = entry.family;
  out["inputs"] = inputs;
  out["targets"] = targets;
  out["sources"] = sources;
  return out;
}

py::dict read_dataset(const std::filesystem::path& dir) {
  const dataset::Manifest manifest = dataset::read_manifest(dir / "manifest.json");
  const double cell = dataset::feature_cell(manifest);
  const int channels = surrogate::input_channels(cell, dataset::physics_input(manifest));
  std::vector<dataset::ShardArrays> shards;
  {
    ReleasedGil release;
    for (const dataset::ManifestShard& entry : manifest.shards)
      shards.push_back(dataset::read_shard(dir, entry, channels));
  }
  py::dict out;
  out["parameters"] = from_json(manifest.generator);
  if (cell > 0) {
    // A physical grid is each map's own size: one dict of arrays per map.
    py::list maps;
    for (std::size_t s = 0; s < shards.size(); ++s)
      maps.append(shard_dict(manifest.shards[s], shards[s]));
    out["feature_cell"] = cell;
    out["maps"] = maps;
    return out;
  }
  const auto n = static_cast<py::ssize_t>(manifest.samples);
  const py::ssize_t ny = shards.empty() ? 64 : shards[0].ny,
                    nx = shards.empty() ? 64 : shards[0].nx;
  py::array_t<float> inputs({n, py::ssize_t{3}, ny, nx}), targets({n, py::ssize_t{2}, ny, nx});
  py::array_t<float> sources({n, py::ssize_t{2}});
  py::array_t<std::int32_t> map_ids(n);
  std::size_t row = 0;
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const dataset::ShardArrays& a = shards[s];
    const std::size_t cells = static_cast<std::size_t>(nx * ny);
    put(inputs, row * 3 * cells, a.inputs);
    put(targets, row * 2 * cells, a.targets);
    put(sources, row * 2, a.sources);
    std::fill_n(map_ids.mutable_data() + row, a.samples, manifest.shards[s].map_index);
    row += static_cast<std::size_t>(a.samples);
  }
  out["inputs"] = inputs;
  out["targets"] = targets;
  out["sources"] = sources;
  out["map_ids"] = map_ids;
  return out;
}

}  // namespace

void bind_dataset(py::module_& m) {
  m.def("read_dataset", &read_dataset, py::arg("dir"),
        "A `plumekit dataset generate` (or `dataset merge`) folder, every shard checked against "
        "its checksums: a dict of numpy arrays 'inputs' float32 [n, 3, 64, 64] (region label, "
        "signed distance, source distance), 'targets' float32 [n, 2, 64, 64] (mean, std), "
        "'sources' [n, 2] (m, arena frame), 'map_ids' [n], and the generator's 'parameters'. "
        "A physical-grid dataset (`dataset generate --feature-cell C`) has each map's own grid: "
        "instead of those arrays, 'feature_cell' (m) and 'maps', a list with one dict per map: "
        "'map_id', 'map' (its file in the folder), 'family', 'inputs' float32 [n, 5, ny, nx] "
        "(region label, signed distance, wind u and v in m/s, source distance), 'targets' "
        "float32 [n, 2, ny, nx], 'sources' [n, 2]. torch.from_numpy() shares their memory.");
}

}  // namespace plumekit::python
