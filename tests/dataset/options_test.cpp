// The dataset's options checks: every defect is refused by the library with
// the field and the range, before generate_dataset writes anything, and the
// filament model's memory guard. CLI: exit 2 and no output left behind.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cfd/flow_solver.hpp"
#include "core/memory_limit.hpp"
#include "dataset/generator.hpp"
#include "support/cli_runner.hpp"

namespace plumekit::dataset {
namespace {

namespace fs = std::filesystem;

class MemoryLimitScope {
 public:
  explicit MemoryLimitScope(double bytes) { set_memory_limit(bytes); }
  ~MemoryLimitScope() { set_memory_limit(default_memory_limit()); }
};

void expect_has(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << part << "' not in: " << text;
}

// generate_dataset on a fresh path must throw OptionError on `field` and leave
// the path absent.
void expect_refused(const DatasetOptions& o, const std::string& field, const std::string& part) {
  const fs::path out = fs::temp_directory_path() / ("plumekit_options_" + std::to_string(getpid()));
  fs::remove_all(out);
  try {
    generate_dataset(out, o, {});
    ADD_FAILURE() << field << ": no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), field);
    expect_has(e.message(), part);
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out)) << field << ": generate_dataset wrote before validating";
  fs::remove_all(out);
}

DatasetOptions small() {
  DatasetOptions o;
  o.maps = 1;
  o.sources = 1;
  o.flow.cell = 0.1;
  return o;
}

TEST(DatasetOptions, DefectsAreRefusedBeforeAnythingIsWritten) {
  DatasetOptions o = small();
  o.flow.cell = -0.05;  // 0 is the default: from the map's size
  expect_refused(o, "flow.cell", "more than 0 and at most 10 m, got -0.05");
  o.flow.cell = NAN;
  expect_refused(o, "flow.cell", "got nan");
  o = small();
  o.map.families = {"l-shape", "U"};
  expect_refused(o, "maps.families", "unknown name 'U'; use rectangle, two-rectangles, l-shape");
  o = small();
  o.plume.filament.release_per_second = 0.0;
  expect_refused(o, "plume.filaments_per_second", "got 0");
  o = small();
  o.plume.advection_diffusion.release_rate = NAN;
  expect_refused(o, "plume.release_rate", "got nan");
  o = small();
  o.plume.filament.release_rate = -5.0;
  expect_refused(o, "plume.release_rate", "got -5");
  o = small();
  o.plume.advection_diffusion.diffusivity = 1e300;
  expect_refused(o, "plume.diffusivity", "got 1e+300");
  o = small();
  o.maps = 0;
  expect_refused(o, "dataset.maps", "from 1 to");
  o = small();
  o.map.width = 1e5;
  expect_refused(o, "maps.width", "at most 100 m, got 1e+05");
}

TEST(DatasetOptions, ThreadsThatWouldExhaustMemoryAreRefused) {
  const MemoryLimitScope scope(parse_memory_size("256M"));
  DatasetOptions o = small();
  o.flow.cell = 0.05;  // ~90 MB per thread
  RunOptions run;
  run.threads = 8;
  const fs::path out = fs::temp_directory_path() / ("plumekit_threads_" + std::to_string(getpid()));
  try {
    generate_dataset(out, o, run);
    ADD_FAILURE() << "no MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    expect_has(e.what(), "8 worker threads");
    expect_has(e.what(), "use fewer dataset.threads (");
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST(FilamentModel, FilamentCountOverTheLimitIsRefusedWithTheRateThatFits) {
  const MemoryLimitScope scope(parse_memory_size("64M"));
  world::FilamentOptions o;
  o.release_per_second = 1e5;  // 6.5 million filaments: 312 MB
  const Map map = default_arena();
  cfd::FlowOptions fo;
  fo.cell = 0.2;
  const cfd::WindField wind = cfd::solve(map, fo).wind;
  try {
    world::FilamentSimulation sim(map, wind, {1.0, 2.0}, o, 1);
    ADD_FAILURE() << "no MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    expect_has(e.what(), "1e+05 filaments per second");
    expect_has(e.what(), "use fewer plume.filaments_per_second (");
  }
  o.release_per_second = 1e9;  // the 12 GB run: out of range whatever the limit
  try {
    world::FilamentSimulation sim(map, wind, {1.0, 2.0}, o, 1);
    ADD_FAILURE() << "no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "plume.filaments_per_second");
  }
}

TEST(RandomMapOptions, ValidateNamesTheField) {
  RandomMapOptions o;
  EXPECT_NO_THROW(o.validate());
  o.families.clear();
  EXPECT_THROW(o.validate(), OptionError);
  o = RandomMapOptions{};
  o.min_gap = NAN;
  try {
    random_map(o, 0, 0);
    ADD_FAILURE();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "maps.min_gap");
  }
}

class DatasetOptionsCli : public test::CliTest {};

TEST_F(DatasetOptionsCli, BadValuesExitTwoAndLeaveNoOutput) {
  const fs::path out = dir / "D";
  struct Case {
    const char* args;
    const char* says;
  } cases[] = {
      {"--cell -1", "more than 0 and at most 10 m, got -1"},
      {"--cell nan", "got nan"},
      {"--families l-shape,U", "unknown name 'U'"},
      {"--filaments-per-second 0", "got 0"},
      {"--release-rate nan", "got nan"},
      {"--release-rate -5", "got -5"},
  };
  for (const Case& c : cases) {
    const auto r = run("dataset generate --maps 1 --sources 1 " + std::string(c.args) + " --out " +
                       out.string());
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    expect_has(r.err, c.says);
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace plumekit::dataset
