// STE's options: the library's defaults (the surrogate, its sigmas and grid
// following the model), each field refused by the library with its name and
// range (before the wind is solved), and oversized source grids refused.
#include <gtest/gtest.h>

#include <cmath>

#include "core/memory_limit.hpp"
#include "run/evaluation.hpp"
#include "run/scenario.hpp"

namespace plumekit::ste {
namespace {

// A model file for the checks that need one to exist (its content is not read).
const std::string kModel = std::string(PLUMEKIT_DATA_DIR) + "/models/plume-unet.pkcnn";

void expect_has(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

template <class F>
void expect_option_error(F&& f, const std::string& field, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << field << ": no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), field);
    expect_has(e.message(), part);
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
  }
}

TEST(SteOptions, EveryDefectNamesTheFieldAndTheRange) {
  struct Case {
    const char* field;
    void (*set)(run::SteOptions&);
    const char* says;
  } cases[] = {
      {"ste.world.noise", [](run::SteOptions& o) { o.world.noise = NAN; }, "got nan"},
      {"ste.world.noise", [](run::SteOptions& o) { o.world.noise = -1.0; }, "got -1"},
      {"ste.world.speed", [](run::SteOptions& o) { o.world.speed = 0.0; }, "more than 0"},
      {"ste.likelihood.sigma_m", [](run::SteOptions& o) { o.likelihood.sigma_m = INFINITY; },
       "got inf"},
      {"ste.likelihood.sigma_m",
       [](run::SteOptions& o) {
         o.likelihood.sigma_m = 0.0;
         o.likelihood.sigma_d = 0.0;
       },
       "both 0"},
      {"ste.navigation.alpha", [](run::SteOptions& o) { o.navigation.alpha = 1.5; }, "from 0 to 1"},
      {"ste.navigation.lattice", [](run::SteOptions& o) { o.navigation.lattice = 0; },
       "from 1 to 20"},
      {"ste.stop.max_samples", [](run::SteOptions& o) { o.stop.max_samples = -1; }, "from 0"},
      {"ste.mh.burn_in", [](run::SteOptions& o) { o.mh.burn_in = 5000; }, "from 0 to 3999"},
      {"ste.physics.source_cell", [](run::SteOptions& o) { o.physics.source_cell = NAN; },
       "got nan"},
      {"ste.source_cell",
       [](run::SteOptions& o) {
         o.model = run::PlumeModelKind::Physics;
         o.source_cell = 0.0;
       },
       "more than 0"},
      {"ste.source_cell",
       [](run::SteOptions& o) {
         o.model = run::PlumeModelKind::Gaussian;
         o.source_cell = 0.2;
       },
       "only the surrogate and physics"},
      {"ste.likelihood.sigma_std",
       [](run::SteOptions& o) {
         o.model = run::PlumeModelKind::Physics;
         o.likelihood.sigma_std = 2.0;
       },
       "only the surrogate"},
      {"ste.model_path", [](run::SteOptions& o) { o.model_path = "/nonexistent/x.pkcnn"; },
       "/nonexistent/x.pkcnn not found"},
      {"ste.model_path", [](run::SteOptions& o) { o.model_path.clear(); },
       "needs a CNN model file"},
      {"flow.cell", [](run::SteOptions& o) { o.flow.cell = -1.0; }, "got -1"},
      {"ste.physics.scale_hi", [](run::SteOptions& o) { o.physics.scale_hi = 0.5; }, "from 1 to"},
      {"plume.release_rate", [](run::SteOptions& o) { o.world.filament.release_rate = NAN; },
       "got nan"},
      {"plume.diffusivity",
       [](run::SteOptions& o) { o.physics.advection_diffusion.diffusivity = -1.0; }, "got -1"},
      {"ste.margin", [](run::SteOptions& o) { o.margin = 1e300; }, "got 1e+300"},
  };
  const Map map = default_arena();
  for (const Case& c : cases) {
    run::SteOptions o;
    o.model_path = kModel;
    c.set(o);
    expect_option_error([&] { run::Scenario s(map, o); }, c.field, c.says);
  }
  run::SteOptions o;
  o.model_path = kModel;
  EXPECT_NO_THROW(o.validate());
}

TEST(SteOptions, DefaultsAreTheSurrogatesAndFollowTheModel) {
  run::SteOptions o;
  EXPECT_EQ(o.model, run::PlumeModelKind::Surrogate);
  EXPECT_EQ(o.threads, kDefaultThreads);
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_m, 200.0);
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_std, 1.0);  // the moving protocol's
  EXPECT_DOUBLE_EQ(o.source_cell_in_use(), 0.2);
  o.model = run::PlumeModelKind::Physics;
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_m, 150.0);
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_std, 0.0);
  EXPECT_DOUBLE_EQ(o.source_cell_in_use(), 0.1);
  o.model = run::PlumeModelKind::Gaussian;
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_m, 30.0);
  EXPECT_DOUBLE_EQ(o.source_cell_in_use(), 0.0);
  o.likelihood.sigma_m = 55.0;  // a value given wins over the model's
  o.source_cell = 0.3;
  o.model = run::PlumeModelKind::Physics;
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_m, 55.0);
  EXPECT_DOUBLE_EQ(o.source_cell_in_use(), 0.3);
  EXPECT_EQ(parse_reward(to_string(NavigationOptions::Reward::Kl)), NavigationOptions::Reward::Kl);
  expect_option_error([] { parse_reward("greedy"); }, "ste.navigation.reward", "'greedy'");
  EXPECT_EQ(o.navigation.candidates, NavigationOptions::Candidates::Auto);
  EXPECT_EQ(parse_candidates("auto"), NavigationOptions::Candidates::Auto);
  EXPECT_EQ(parse_candidates(to_string(NavigationOptions::Candidates::Floor)),
            NavigationOptions::Candidates::Floor);
  expect_option_error([] { parse_candidates("rooms"); }, "ste.navigation.candidates", "'rooms'");
  o.navigation.floor_gain_cells = 8;
  expect_option_error([&] { o.navigation.validate(); }, "ste.navigation.floor_gain_cells", "got 8");
  o.stop.seen_mass = 1.5;
  expect_option_error([&] { o.stop.validate(); }, "ste.stop.seen_mass", "got 1.5");
  expect_option_error([] { run::parse_plume_model_kind("kriging"); }, "ste.model", "'kriging'");
}

// Issue 47: the default protocol reads on the way and stops adaptively; the thesis's preset turns
// both off and brings back its likelihood; either half can be set over the preset.
TEST(SteOptions, TheProtocolPresetSetsTheWorldsHalvesAndTheLikelihood) {
  run::SteOptions o;
  EXPECT_EQ(o.protocol, run::SamplingProtocol::Moving);
  EXPECT_TRUE(o.world.read_while_moving);
  EXPECT_TRUE(o.world.adaptive_stop);
  EXPECT_DOUBLE_EQ(o.stop.confidence_radius, 0.3);
  EXPECT_DOUBLE_EQ(o.stop.confidence_mass, 0.95);
  EXPECT_TRUE(o.approach);
  EXPECT_FALSE(world::WorldOptions{}.read_while_moving);        // the world alone reads where told
  EXPECT_DOUBLE_EQ(ste::StopOptions{}.confidence_radius, 0.0);  // STE alone: the thesis's rule
  run::set_protocol(o, run::parse_sampling_protocol("thesis"));
  EXPECT_FALSE(o.world.read_while_moving);
  EXPECT_FALSE(o.world.adaptive_stop);
  EXPECT_DOUBLE_EQ(o.stop.confidence_radius, 0.0);
  EXPECT_FALSE(o.approach);
  EXPECT_EQ(o.stop.max_samples, ste::StopOptions{}.max_samples);  // the rest untouched
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_std, 2.0);
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_m, 200.0);
  o.likelihood.sigma_std = 1.5;  // a value given wins over the protocol's
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_std, 1.5);
  o.world.adaptive_stop = true;
  run::set_protocol(o, run::SamplingProtocol::Moving);
  EXPECT_TRUE(o.world.read_while_moving && o.world.adaptive_stop);
  EXPECT_STREQ(run::to_string(o.protocol), "moving");
  // Only the surrogate's likelihood depends on it.
  o.model = run::PlumeModelKind::Physics;
  const double physics_moving = o.likelihood_options().sigma_m;
  run::set_protocol(o, run::SamplingProtocol::Thesis);
  EXPECT_DOUBLE_EQ(o.likelihood_options().sigma_m, physics_moving);
  expect_option_error([] { run::parse_sampling_protocol("drive-by"); }, "ste.protocol",
                      "'drive-by'");
}

TEST(EvaluationOptions, CountsAreCheckedBeforeAnyWork) {
  run::EvaluationOptions o;
  o.runs = 0;
  expect_option_error([&] { evaluate({default_arena()}, o); }, "evaluation.runs", "from 1");
  o = run::EvaluationOptions{};
  o.ste.world.noise = NAN;
  expect_option_error([&] { evaluate({default_arena()}, o); }, "ste.world.noise", "got nan");
}

TEST(Scenario, FlowCellFaultNamesTheFlowCell) {
  // Two blocks 3 cm apart: the flow's 5 cm grid would close the gap; ste's flow.cell can fix it.
  Map map = default_arena();
  map.name = "narrow";
  map.obstacles.push_back({{3.0, 0.0}, {4.0, 0.0}, {4.0, 1.9}, {3.0, 1.9}});
  map.obstacles.push_back({{3.0, 1.93}, {4.0, 1.93}, {4.0, 4.0}, {3.0, 4.0}});
  run::SteOptions o;
  o.model = run::PlumeModelKind::Gaussian;
  o.flow.strict_gaps = true;  // by default the grid closes the gap, with a warning
  expect_option_error([&] { run::Scenario s(map, o); }, "flow.cell", "0.03 m apart");
}

TEST(SteOptions, TableCellIsAtLeastTheSourceCellAndOnlyTheSurrogates) {
  run::SteOptions o;
  o.model_path = kModel;
  o.source_cell = 0.3;
  o.table_cell = 0.2;
  expect_option_error([&] { o.validate(); }, "ste.table_cell", "at least the source cell");
  o.table_cell = 0.3;
  EXPECT_NO_THROW(o.validate());
  o.model = run::PlumeModelKind::Physics;
  expect_option_error([&] { o.validate(); }, "ste.table_cell", "only the surrogate has a table");
}

TEST(Scenario, OversizedSourceGridIsRefused) {
  run::SteOptions o;
  o.model = run::PlumeModelKind::Physics;
  o.source_cell = 1e-4;  // 100000 x 40000 candidate cells
  expect_option_error([&] { run::Scenario s(default_arena(), o); }, "ste.source_cell",
                      "more than 1e+08");
  set_memory_limit(parse_memory_size("64M"));
  o.source_cell = 0.005;  // 1.6 million cells, 410 MB
  try {
    run::Scenario s(default_arena(), o);
    ADD_FAILURE() << "no MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    expect_has(e.what(), "use a larger ste.source_cell (");
  }
  // The surrogate's table keeps two 64 x 64 plumes per cell: 2 cm cells on 10 x 4 m are 3.3 GB.
  set_memory_limit(parse_memory_size("1G"));
  run::SteOptions surrogate;
  surrogate.model_path = kModel;
  surrogate.source_cell = 0.02;
  try {
    run::Scenario s(default_arena(), surrogate);
    ADD_FAILURE() << "no MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    expect_has(e.what(), "the surrogate table of 100000 table cells x 4096 plume cells");
    expect_has(e.what(), "use a larger ste.table_cell (or ste.source_cell)");
  }
  set_memory_limit(default_memory_limit());
}

}  // namespace
}  // namespace plumekit::ste
