// The shipped model files' provenance names no path of the machine that trained them, and each
// file still passes its own checksum; the fine-tuned model names its start by the start's SHA-256.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/sha256.hpp"
#include "surrogate/model_file.hpp"

namespace plumekit::surrogate {
namespace {

namespace fs = std::filesystem;
const fs::path kModels = fs::path(PLUMEKIT_DATA_DIR) / "models";

void absolute_paths(const nlohmann::json& j, const std::string& where,
                    std::vector<std::string>& out) {
  if (j.is_string() && fs::path(j.get<std::string>()).is_absolute()) out.push_back(where);
  if (j.is_object())
    for (const auto& [k, v] : j.items())
      absolute_paths(v, where + "." + k, out);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i)
      absolute_paths(j[i], where + "[" + std::to_string(i) + "]", out);
}

TEST(Provenance, ShippedModelsHoldNoAbsolutePath) {
  for (const char* name : {"plume-unet.pkcnn", "plume-unet-base.pkcnn"}) {
    const ModelFile m = read_model_file(kModels / name);  // checks the whole-file SHA-256
    const auto header = nlohmann::json::parse(m.header_json);
    ASSERT_TRUE(header.contains("training")) << name;
    std::vector<std::string> bad;
    absolute_paths(header, "header", bad);
    EXPECT_TRUE(bad.empty()) << name << ": " << (bad.empty() ? "" : bad[0]);
    EXPECT_FALSE(header["training"]["dataset"].get<std::string>().empty()) << name;
  }
}

TEST(Provenance, TheFineTunedModelNamesItsStartByItsChecksum) {
  const auto header =
      nlohmann::json::parse(read_model_file(kModels / "plume-unet.pkcnn").header_json);
  const auto& init = header["training"]["init"];
  EXPECT_EQ(init["model"], "plume-unet-base.pkcnn");
  EXPECT_EQ(init["sha256"], sha256_file(kModels / "plume-unet-base.pkcnn"));
}

}  // namespace
}  // namespace plumekit::surrogate
