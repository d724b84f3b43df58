// Datasets (dataset/): a `plumekit dataset generate` folder read back whole, every file checked.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "core/error.hpp"
#include "dataset/dataset_reader.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace plumekit::python {

namespace {

// Appends `values` into `out` at `offset` (elements), the arrays being preallocated.
template <class T>
void put(py::array_t<T>& out, std::size_t offset, const std::vector<T>& values) {
  std::copy(values.begin(), values.end(), out.mutable_data() + offset);
}

py::dict read_dataset(const std::filesystem::path& dir) {
  const dataset::Manifest manifest = dataset::read_manifest(dir / "manifest.json");
  if (dataset::feature_cell(manifest) > 0)
    throw plumekit::InputError(
        (dir / "manifest.json").string() +
        ": a physical-grid dataset (generator.feature_cell) has one grid per map, "
        "which read_dataset's single arrays cannot hold; read it with "
        "surrogate/train/shards.py");
  std::vector<dataset::ShardArrays> shards;
  {
    ReleasedGil release;
    for (const dataset::ManifestShard& entry : manifest.shards)
      shards.push_back(dataset::read_shard(dir, entry, 3));
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
  py::dict out;
  out["inputs"] = inputs;
  out["targets"] = targets;
  out["sources"] = sources;
  out["map_ids"] = map_ids;
  out["parameters"] = from_json(manifest.generator);
  return out;
}

}  // namespace

void bind_dataset(py::module_& m) {
  m.def("read_dataset", &read_dataset, py::arg("dir"),
        "A `plumekit dataset generate` (or `dataset merge`) folder, every shard checked against "
        "its checksums: a dict of numpy arrays 'inputs' float32 [n, 3, 64, 64] (region label, "
        "signed distance, source distance), 'targets' float32 [n, 2, 64, 64] (mean, std), "
        "'sources' [n, 2] (m, arena frame), 'map_ids' [n], and the generator's 'parameters'. "
        "torch.from_numpy() shares their memory.");
}

}  // namespace plumekit::python
