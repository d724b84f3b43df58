// The part folder reader of `evaluate merge` (ste/evaluation_part_reader): counts beyond what
// evaluate writes are refused before check_part_coverage multiplies them (issue 44, found reading
// the code while fuzzing: pairs.total * K overflowed a long long).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/sha256.hpp"
#include "run/evaluation_part_reader.hpp"
#include "run/run_tracks.hpp"

namespace plumekit::ste {
namespace {

namespace fs = std::filesystem;

// A part folder of part K of N with no runs and `total` pairs in all, sealed as evaluate seals it
// (`threads` as given).
fs::path write_part(const std::string& name, int k, int n, long long total,
                    const nlohmann::ordered_json& threads = 1) {
  const fs::path dir = fs::temp_directory_path() /
                       ("plumekit-parts-test-" + std::to_string(::getpid()) + "-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string runs = "map,source_index,run\n", timings = "map,source_index,run\n",
                    tracks = R"({"format":"plumekit-tracks/1","maps":[],"runs":[]})";
  nlohmann::ordered_json j{
      {"format", run::kPartFormat},
      {"part", k},
      {"parts", n},
      {"pairs", {{"first", 0}, {"end", 0}, {"total", total}}},
      {"settings", {{"runs_per_source", 1}, {"seeds", 1}, {"plume_model", "gaussian"}}},
      {"options", nlohmann::ordered_json::object()},
      {"maps", {{{"name", "m"}}}},
      {"files",
       {{"runs.csv", sha256_hex(runs)},
        {"timings.csv", sha256_hex(timings)},
        {"tracks.json", sha256_hex(tracks)}}},
      {"threads", threads},
      {"wall_s", 1.0},
      {"map_times", {{{"ran", false}, {"wind_s", 0.0}, {"table_build_s", 0.0}, {"wall_s", 0.0}}}},
      {"runs", nlohmann::ordered_json::array()}};
  j["sha256"] = run::part_body_sha256(j);
  std::ofstream(dir / run::kPartFile) << j.dump(2);
  std::ofstream(dir / "runs.csv") << runs;
  std::ofstream(dir / "timings.csv") << timings;
  std::ofstream(dir / "tracks.json") << tracks;
  return dir;
}

TEST(EvaluationParts, APartThatEvaluateCouldHaveWrittenIsRead) {
  const fs::path dir = write_part("ok", 0, 1, 0);
  const run::EvaluationPart p = run::read_evaluation_part(dir);
  EXPECT_EQ(p.n, 1);
  EXPECT_NO_THROW(run::check_part_coverage({p}));
  fs::remove_all(dir);
}

TEST(EvaluationParts, CountsBeyondWhatEvaluateWritesAreRefusedNamingTheKey) {
  const fs::path dir = write_part("huge", 1, 3, 1LL << 40);
  try {
    run::read_evaluation_part(dir);
    FAIL() << "a part of 2^40 pairs was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pairs.total is 1099511627776, outside 0.."),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

// A float where evaluate writes an integer is refused, not cast (1e60 to an int is undefined
// behaviour; fuzz/corpus/fuzz_evaluate_part/float-count is the fuzzer's case).
TEST(EvaluationParts, AFloatWhereAWholeNumberBelongsIsRefusedNamingTheKey) {
  const fs::path dir = write_part("float", 0, 1, 0, 1.44444e60);
  try {
    run::read_evaluation_part(dir);
    FAIL() << "threads 1.44444e60 was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("threads is 1.44444e+60, not a whole number"),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace plumekit::ste

namespace plumekit::run {
namespace {

// tracks.json as evaluate writes it is read; anything else is refused naming the file and what.
TEST(EvaluationTracks, MalformedTracksAreRefusedNamingTheFileAndTheRun) {
  const std::string good =
      R"({"format":"plumekit-tracks/1","maps":[],"runs":[{"source":[1,2],"estimate":[1.1,2],)"
      R"("robots":[{"path":[0,0,1,0],"stops":[1,0,0.5,3.2]}]}]})";
  EXPECT_EQ(parse_tracks(good, "t.json", 1)["runs"].size(), 1u);
  auto refusal = [](const std::string& bytes, std::size_t runs) {
    try {
      parse_tracks(bytes, "dir/tracks.json", runs);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(refusal(good, 2).find("dir/tracks.json: holds 1 runs' tracks, runs.csv 2"),
            std::string::npos);
  EXPECT_NE(refusal("{", 1).find("dir/tracks.json: not plumekit-tracks/1"), std::string::npos);
  for (const char* damage : {R"("path":[0,0,1])", R"("path":[])", R"("path":"x")"}) {
    std::string bad = good;
    bad.replace(bad.find(R"("path":[0,0,1,0])"), 16, damage);
    EXPECT_NE(refusal(bad, 1).find("run 0's track lacks"), std::string::npos) << damage;
  }
  std::string no_robots = good;
  no_robots.replace(no_robots.find("\"robots\""), 8, "\"robot\"");
  EXPECT_NE(refusal(no_robots, 1).find("run 0's track lacks"), std::string::npos);
}

}  // namespace
}  // namespace plumekit::run
