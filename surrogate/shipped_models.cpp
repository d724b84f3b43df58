#include "surrogate/shipped_models.hpp"

namespace plumekit::surrogate {

const std::vector<ShippedModel>& shipped_models() {
  static const std::vector<ShippedModel> models{
      {"hybrid", "plume-unet-v3.pkcnn", "the default; any map"},
      {"thesis", "plume-unet.pkcnn", "the thesis's 64 x 64; 10 x 4 m maps"},
      {"v2", "plume-unet-v2.pkcnn", "any map"},
      {"faithful", "plume-unet-faithful.pkcnn", "the thesis's, faithful world; 10 x 4 m maps"}};
  return models;
}

std::filesystem::path default_model(const std::filesystem::path& data_dir) {
  return resolve_model("hybrid", data_dir);
}

std::filesystem::path thesis_model(const std::filesystem::path& data_dir) {
  return resolve_model("thesis", data_dir);
}

std::filesystem::path resolve_model(const std::string& text,
                                    const std::filesystem::path& data_dir) {
  for (const ShippedModel& m : shipped_models())
    if (text == m.name) return data_dir / "models" / m.file;
  return text;
}

}  // namespace plumekit::surrogate
