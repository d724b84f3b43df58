#pragma once
// The plume models plumekit ships in its data folder (data/models/): named here, once, for the
// CLI and Python alike.
#include <filesystem>

namespace plumekit::surrogate {

// The thesis's 64 x 64 U-Net for 10 x 4 m arenas: what `localize`, `predict` and Python use when
// no model is named.
inline std::filesystem::path thesis_model(const std::filesystem::path& data_dir) {
  return data_dir / "models" / "plume-unet.pkcnn";
}

// The hybrid U-Net on a physical grid (issue 46: the physics plume of the source among its
// inputs), for maps of any size: what the advice on a map the thesis model cannot take names. It
// replaced the v2 model (issue 19, plume-unet-v2.pkcnn, still shipped) there, being better on
// every held-out set (docs/design/surrogate.md, "Hybrid models").
inline std::filesystem::path any_map_model(const std::filesystem::path& data_dir) {
  return data_dir / "models" / "plume-unet-v3.pkcnn";
}

}  // namespace plumekit::surrogate
