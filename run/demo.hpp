#pragma once
// The README's demo (`plumekit demo`): one localization on a shipped test map
// whose obstacles bend the plume, from a start upwind, drawn.
#include <cstdint>
#include <filesystem>
#include <string>

#include "core/geometry.hpp"
#include "core/seed.hpp"
#include "run/localize_job.hpp"
#include "run/scenario.hpp"

namespace plumekit::run {

struct DemoOptions {
  SteOptions ste;
  std::string map_file = "test-4-l-shape.json";  // in the shipped test maps (data/test-maps)
  int source_index = 4;  // (2.23, 2.51): upwind of the L, whose plume bends over it
  Vec2 start{1.0, 1.0};
  std::uint64_t seed = kDefaultSeed;
};

// When no plume model was asked for: the surrogate if its CNN file (ste.model_path) is there,
// else the physics model. Returns a note saying so when it falls back, else "".
std::string choose_demo_model(SteOptions& options);

// The demo's run: its map read from `maps_dir` (the shipped test maps), the run from the demo's
// start, its pictures in the output folder `out`, and the summary, with `note`
// (choose_demo_model's) under "note" when there is one.
LocalizeReport demo_job(const DemoOptions& demo, const std::filesystem::path& maps_dir,
                        const std::filesystem::path& out, const std::string& note);

}  // namespace plumekit::run
