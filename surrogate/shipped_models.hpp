#pragma once
// The plume models plumekit ships in its data folder (data/models/): named here, once, for the
// CLI and Python alike. `--cnn` (and Python's `cnn=`) takes one of these names or a file.
#include <filesystem>
#include <string>
#include <vector>

namespace plumekit::surrogate {

struct ShippedModel {
  const char* name;  // what --cnn takes
  const char* file;  // in data/models/
  const char* what;  // a few words for --help
};

// hybrid (the default), thesis, v2, faithful: in that order.
const std::vector<ShippedModel>& shipped_models();

// The hybrid U-Net on a physical grid (issue 46: the physics plume of the source among its
// inputs), for maps of any size, the thesis's 10 x 4 m arenas included: what `localize`,
// `predict`, `evaluate` and Python use when no model is named. It beat the thesis's model and v2
// on every test and held-out set (docs/design/surrogate.md, "Hybrid models").
std::filesystem::path default_model(const std::filesystem::path& data_dir);
// The thesis's 64 x 64 U-Net for 10 x 4 m arenas (--cnn thesis): for reproducing the thesis.
std::filesystem::path thesis_model(const std::filesystem::path& data_dir);

// `text` as a model file: a shipped model's name becomes its file in `data_dir`/models; anything
// else is a path, returned as given (a file named like a shipped model is reached as ./NAME).
std::filesystem::path resolve_model(const std::string& text, const std::filesystem::path& data_dir);

}  // namespace plumekit::surrogate
