// What the STE commands report: the picture of a map's median run says which
// run it shows and the map's median apart (test-8 once read "S1 ... 1.88 m"
// over a median of 3.07 m), a single run's title gives its source in the map frame, and a map
// folder is read in name order.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "core/error.hpp"
#include "run/render.hpp"
#include "run/report.hpp"

namespace plumekit::ste {
namespace {

run::RunRecord record(int source, int run, double error) {
  run::RunRecord r;
  r.source_index = source;
  r.run = run;
  r.error_m = error;
  return r;
}

TEST(Report, MedianRunIsARealRunAndItsNoteGivesTheMapMedian) {
  // An even count: the map's median (3.07) is no run's error; the run shown is the lower one.
  const std::vector<run::RunRecord> runs{record(0, 0, 4.26), record(1, 0, 1.88)};
  const run::RunRecord& shown = median_run(runs);
  EXPECT_EQ(shown.source_index, 1);
  EXPECT_DOUBLE_EQ(shown.error_m, 1.88);
  EXPECT_EQ(median_run_note(runs), "median run of 2; map median 3.07 m");
  // An odd count: the run shown is the median.
  const std::vector<run::RunRecord> three{record(0, 0, 0.5), record(0, 1, 0.1), record(1, 0, 9.0)};
  EXPECT_DOUBLE_EQ(median_run(three).error_m, 0.5);
  EXPECT_EQ(median_run_note(three), "median run of 3; map median 0.50 m");
}

TEST(Report, MapFolderIsReadInNameOrderWithPictureNamesFromTheFiles) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("ste-report-test-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  EXPECT_THROW(run::read_map_folder(dir), OptionError);
  fs::create_directories(dir);
  try {
    run::read_map_folder(dir);
    ADD_FAILURE() << "no OptionError for an empty folder";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "evaluation.map_dir");
  }
  const std::string map = R"({"format": "plumekit-map/1", "name": "same name", "size": [4, 2],
    "inlet": {"side": "left", "speed": 1.0}, "outlet": {"side": "right"}, "obstacles": [],
    "sources": [[3, 1]]})";
  std::ofstream(dir / "b map.json") << map;
  std::ofstream(dir / "a.json") << map;
  std::ofstream(dir / "notes.txt") << "not a map";
  // The output marker `plumekit maps random --out` leaves is not a map.
  std::ofstream(dir / ".plumekit-output.json") << R"({"format": "plumekit-output/1"})";
  const run::MapFolder f = run::read_map_folder(dir);
  ASSERT_EQ(f.maps.size(), 2u);
  EXPECT_EQ(f.files[0].filename(), "a.json");
  EXPECT_EQ(f.picture_names, (std::vector<std::string>{"a.png", "b_map.png"}));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::ste

namespace plumekit::ste {
namespace {

TEST(Report, ATrajectoryTitleGivesTheSourceInTheMapFrame) {
  Map map = default_arena(30.0, 15.0);
  map.name = "depot";
  map.frame.origin = {-7.0, -8.0};
  run::LocalizationResult result;
  result.estimate = {8.0, 10.0};  // arena coordinates, as the loop keeps them
  result.samples = 3;
  result.stopped_by = "entropy";
  run::RunToDraw run;
  run.result = &result;
  run.source = {8.0, 10.0};  // (1, 2) in the map's frame
  run.model = "physics";
  EXPECT_EQ(
      run::trajectory_title(map, run).rfind("depot: physics, source (1.00, 2.00): error 0.00 m", 0),
      0u)
      << run::trajectory_title(map, run);
}

}  // namespace
}  // namespace plumekit::ste
