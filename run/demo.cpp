#include "run/demo.hpp"

#include <filesystem>

namespace plumekit::run {

std::string choose_demo_model(SteOptions& o) {
  std::error_code ec;
  if (o.model != PlumeModelKind::Surrogate || std::filesystem::is_regular_file(o.model_path, ec))
    return "";
  o.model = PlumeModelKind::Physics;
  return "note: " + o.model_path +
         " is not there yet, so this demo uses the physics plume model; with the trained CNN "
         "it uses the surrogate.";
}

}  // namespace plumekit::run
