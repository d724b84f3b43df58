// `plume`, `maps random`, `dataset generate|show` and `predict` as issue 15 wants them: the
// shared flags (positional MAP, --simulator, --cnn, --map-dir, --seed 1, --threads 0), the old
// spellings as deprecated aliases that do the same and warn, and errors that name the flag.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"

namespace {

namespace fs = std::filesystem;
using plumekit::test::slurp;

const fs::path kData = PLUMEKIT_DATA_DIR;
const std::string kMap = (kData / "maps" / "cluttered-1.json").string();
const std::string kCnn = (kData / "models" / "plume-unet.pkcnn").string();

using Result = plumekit::test::CliResult;
class DatasetCli : public plumekit::test::CliTest {
 protected:
  std::string at(const std::string& name) const { return (dir / name).string(); }
  bool same_file(const std::string& a, const std::string& b) const {
    return slurp(a) == slurp(b) && !slurp(a).empty();
  }
};

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(DatasetCli, HelpShowsTheSharedDefaults) {
  const Result generate = run("dataset generate --help");
  EXPECT_TRUE(has(generate.out, "--seed UINT=1")) << generate.out;
  EXPECT_TRUE(has(generate.out, "-j,--threads INT=0")) << generate.out;
  EXPECT_TRUE(has(generate.out, "--simulator")) << generate.out;
  EXPECT_TRUE(has(generate.out, "--map-dir")) << generate.out;
  EXPECT_FALSE(has(generate.out, "--from-maps")) << "a deprecated alias is hidden";
  const Result plume = run("plume --help");
  EXPECT_TRUE(has(plume.out, "--seed UINT=1")) << plume.out;
  EXPECT_TRUE(has(plume.out, "MAP")) << plume.out;
  EXPECT_TRUE(has(plume.out, "=filament")) << plume.out;
  EXPECT_TRUE(has(plume.out, "--release-rate FLOAT=1000")) << plume.out;
  const Result predict = run("predict --help");
  EXPECT_TRUE(has(predict.out, "-j,--threads INT=0")) << predict.out;
  EXPECT_TRUE(has(predict.out, "--cnn")) << predict.out;
  EXPECT_TRUE(has(predict.out, "[MAP]")) << predict.out;
  EXPECT_TRUE(has(run("maps random --help").out, "--seed UINT=1"));
}

// The default seed is 1: a seedless filament plume is the --seed 1 plume, not the --seed 0 one.
TEST_F(DatasetCli, PlumeDefaultsToSeedOne) {
  const std::string common = " --source 1,1 --cell 0.1 --out ";
  ASSERT_EQ(run("plume" + common + at("none")).code, 0);
  ASSERT_EQ(run("plume --seed 1" + common + at("one")).code, 0);
  ASSERT_EQ(run("plume --seed 0" + common + at("zero")).code, 0);
  EXPECT_TRUE(same_file(at("none/mean.npy"), at("one/mean.npy")));
  EXPECT_FALSE(same_file(at("none/mean.npy"), at("zero/mean.npy")));
}

// Where the filaments went: every one released is still alive, left through an outlet, or was
// dropped once too wide (the world's only mass sink besides the outlets).
TEST_F(DatasetCli, PlumeJsonAccountsForEveryFilament) {
  const Result r = run("plume --source 1,1 --cell 0.1 --json --out " + at("count"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto f = nlohmann::json::parse(r.out).at("filament");
  const long long released = f.at("released").get<long long>();
  EXPECT_GT(released, 1000);
  EXPECT_GT(f.at("left_through_outlet").get<long long>(), 0);
  EXPECT_EQ(released, f.at("filaments_at_end").get<long long>() +
                          f.at("left_through_outlet").get<long long>() +
                          f.at("dropped_too_wide").get<long long>());
}

// --occlusion on|off (issue 18): behind the baffles the plume differs, the dataset records the
// setting, and a value other than on or off is refused naming the flag.
TEST_F(DatasetCli, OcclusionIsASwitchTheDatasetRecords) {
  const std::string map = (kData / "test-maps" / "test-8-baffles.json").string();
  const std::string common = " " + map + " --source 5.3,1 --cell 0.1 --out ";
  ASSERT_EQ(run("plume --occlusion off" + common + at("off")).code, 0);
  const Result on = run("plume" + common + at("on"));  // on by default
  ASSERT_EQ(on.code, 0) << on.err;
  EXPECT_FALSE(same_file(at("off/mean.npy"), at("on/mean.npy")));
  const Result bad = run("plume --occlusion maybe" + common + at("bad"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_TRUE(has(bad.err, "--occlusion")) << bad.err;
  EXPECT_FALSE(fs::exists(at("bad")));

  const Result gen = run("dataset generate --maps 1 --sources 2 --occlusion on --out " + at("d"));
  ASSERT_EQ(gen.code, 0) << gen.err;
  EXPECT_TRUE(has(slurp(at("d/manifest.json")), "\"occlusion\": true"));
  const Result off =
      run("dataset generate --maps 1 --sources 2 --occlusion off --out " + at("d-off"));
  ASSERT_EQ(off.code, 0) << off.err;
  EXPECT_FALSE(has(slurp(at("d-off/manifest.json")), "\"occlusion\""));
}

// --wind-model steady|unsteady (issue 18): the same seed gives another plume in the meandering
// wind, the same bytes twice, the dataset records it, and an unknown model is refused.
TEST_F(DatasetCli, TheWindModelIsASwitchTheDatasetRecords) {
  const std::string common = " " + kMap + " --source 1.5,1 --cell 0.1 --out ";
  ASSERT_EQ(run("plume --wind-model steady" + common + at("steady")).code, 0);
  for (const char* dir : {"unsteady", "again"}) {
    const Result r = run("plume" + common + at(dir));  // unsteady by default
    ASSERT_EQ(r.code, 0) << r.err;
  }
  EXPECT_FALSE(same_file(at("steady/mean.npy"), at("unsteady/mean.npy")));
  EXPECT_TRUE(same_file(at("unsteady/mean.npy"), at("again/mean.npy")));
  const Result bad = run("plume --wind-model gusty" + common + at("bad"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_TRUE(has(bad.err, "--wind-model")) << bad.err;
  EXPECT_TRUE(has(bad.err, "steady or unsteady")) << bad.err;
  EXPECT_FALSE(fs::exists(at("bad")));

  const Result gen =
      run("dataset generate --maps 1 --sources 2 --wind-model unsteady --out " + at("d"));
  ASSERT_EQ(gen.code, 0) << gen.err;
  EXPECT_TRUE(has(slurp(at("d/manifest.json")), "\"wind_model\": \"unsteady\"")) << gen.err;
}

// --world (issue 18): thesis turns occlusion and the unsteady wind off, and is then the same plume
// as the two flags; a flag given with it overrides its half; an unknown world is refused.
TEST_F(DatasetCli, TheWorldPresetSetsBothIngredientsAndAFlagOverridesIt) {
  const std::string map = (kData / "test-maps" / "test-1-block.json").string();
  const std::string common = " " + map + " --source 6,2 --cell 0.1 --out ";
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"--world thesis", "thesis"},
      {"--occlusion off --wind-model steady", "flags"},
      {"--world faithful", "faithful"},
      {"", "default"},
      {"--world thesis --occlusion on", "thesis-occluded"},
      {"--occlusion on --wind-model steady", "steady-occluded"}};
  for (const auto& [flags, dir] : runs) {
    const Result r = run("plume " + flags + common + at(dir));
    ASSERT_EQ(r.code, 0) << flags << ": " << r.err;
  }
  EXPECT_TRUE(same_file(at("thesis/mean.npy"), at("flags/mean.npy")));
  EXPECT_TRUE(same_file(at("faithful/mean.npy"), at("default/mean.npy")));
  EXPECT_FALSE(same_file(at("thesis/mean.npy"), at("faithful/mean.npy")));
  EXPECT_TRUE(same_file(at("thesis-occluded/mean.npy"), at("steady-occluded/mean.npy")));
  EXPECT_FALSE(same_file(at("thesis-occluded/mean.npy"), at("thesis/mean.npy")));
  const Result bad = run("plume --world real" + common + at("bad"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_TRUE(has(bad.err, "--world")) << bad.err;
  EXPECT_TRUE(has(bad.err, "faithful, thesis or neumann")) << bad.err;
  EXPECT_FALSE(fs::exists(at("bad")));
}

// --gas-sensor and --baseline on the static sensors (issue 18): the record changes, the dataset
// records the sensor, and the steady advection-diffusion plume refuses a sensor with a response.
TEST_F(DatasetCli, TheStaticSensorsGasSensorIsASettingTheDatasetRecords) {
  const std::string common = " " + kMap + " --source 1.5,1 --cell 0.1 --out ";
  ASSERT_EQ(run("plume" + common + at("ideal")).code, 0);
  const Result mox = run("plume --gas-sensor mox-fast" + common + at("mox"));
  ASSERT_EQ(mox.code, 0) << mox.err;
  EXPECT_FALSE(same_file(at("ideal/mean.npy"), at("mox/mean.npy")));
  const Result ad =
      run("plume --simulator advection-diffusion --gas-sensor catalytic" + common + at("ad"));
  EXPECT_EQ(ad.code, 2);
  EXPECT_TRUE(has(ad.err, "--gas-sensor")) << ad.err;
  EXPECT_TRUE(has(ad.err, "needs the filament model")) << ad.err;
  EXPECT_FALSE(fs::exists(at("ad")));

  const Result gen =
      run("dataset generate --maps 1 --sources 2 --gas-sensor mox-fast --baseline "
          "3 --out " +
          at("d"));
  ASSERT_EQ(gen.code, 0) << gen.err;
  const nlohmann::json m = nlohmann::json::parse(slurp(at("d/manifest.json")));
  const std::string dump = m.dump();
  EXPECT_TRUE(has(dump, "\"gas\":\"mox-fast\"")) << dump;
  EXPECT_TRUE(has(dump, "\"baseline\":3.0")) << dump;
}

// The simulator was --plume-model, a name `localize` gives the estimator's model: the old
// spellings still work, with a warning naming --simulator.
TEST_F(DatasetCli, OldSimulatorSpellingsWarnAndDoTheSame) {
  const std::string common = " --source 1,1 --cell 0.1 --json --out ";
  const Result now = run("plume " + kMap + " --simulator advection-diffusion" + common + at("a"));
  ASSERT_EQ(now.code, 0) << now.err;
  EXPECT_EQ(nlohmann::json::parse(now.out)["model"], "advection-diffusion");
  EXPECT_TRUE(now.err.empty()) << now.err;
  for (const std::string old : {"--plume-model", "--model", "--plume"}) {
    const std::string out = at("old" + old);
    const Result r = run("plume " + kMap + " " + old + " advection-diffusion" + common + out);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.err, old + " is deprecated")) << r.err;
    EXPECT_TRUE(has(r.err, "--simulator")) << r.err;
    EXPECT_TRUE(same_file(at("a/mean.npy"), out + "/mean.npy")) << old;
  }
  const Result both = run("plume --model filament --simulator filament" + common + at("b"));
  EXPECT_EQ(both.code, 2);
  const Result bad = run("plume --simulator gaussian" + common + at("c"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_TRUE(has(bad.err, "--simulator")) << bad.err;
  const Result number = run("plume --simulator 1" + common + at("d"));
  EXPECT_EQ(number.code, 2) << "the enum's number is no kind";
  EXPECT_TRUE(has(number.err, "use filament or advection-diffusion")) << number.err;
}

TEST_F(DatasetCli, MapDirAndItsOldSpellingMakeTheSameDataset) {
  ASSERT_EQ(run("maps random --count 1 --sources 2 --out " + at("maps")).code, 0);
  const std::string common = " --cell 0.1 --simulator advection-diffusion --out ";
  const Result now = run("dataset generate --map-dir " + at("maps") + common + at("new"));
  ASSERT_EQ(now.code, 0) << now.err;
  const Result old = run("dataset generate --from-maps " + at("maps") + common + at("old"));
  ASSERT_EQ(old.code, 0) << old.err;
  EXPECT_TRUE(has(old.err, "--from-maps is deprecated")) << old.err;
  EXPECT_TRUE(same_file(at("new/manifest.json"), at("old/manifest.json")));
  const Result missing = run("dataset generate --map-dir " + at("nowhere") + common + at("x"));
  EXPECT_EQ(missing.code, 2);
  EXPECT_TRUE(has(missing.err, "--map-dir")) << missing.err;
  EXPECT_FALSE(has(missing.err, "dataset.map_dir")) << "the field is shown as its flag";
}

TEST_F(DatasetCli, ErrorsNameTheFlags) {
  const Result shard = run("dataset generate --maps 2 --shard 3/2 --out " + at("d"));
  EXPECT_EQ(shard.code, 2);
  EXPECT_TRUE(has(shard.err, "--shard")) << shard.err;
  const Result threads = run("dataset generate --maps 2 --threads -1 --out " + at("d"));
  EXPECT_EQ(threads.code, 2);
  EXPECT_TRUE(has(threads.err, "--threads")) << threads.err;
  const Result count = run("maps random --count 0 --out " + at("m"));
  EXPECT_EQ(count.code, 2);
  EXPECT_TRUE(has(count.err, "--count")) << count.err;
  const Result source = run("plume --source 3.2,1.0 --out " + at("p"));
  EXPECT_EQ(source.code, 2);
  EXPECT_TRUE(has(source.err, "--source")) << source.err;
  EXPECT_FALSE(fs::exists(at("d")) || fs::exists(at("m")) || fs::exists(at("p")));
}

// Issue 44: merge checks what the checksums do not cover (a manifest's sample count against the
// shard's arrays), and a part folder given twice is named as such, not as a missing part.
TEST_F(DatasetCli, MergeRefusesAWrongSampleCountAndAPartGivenTwice) {
  const std::string common =
      "dataset generate --maps 2 --sources 1 --cell 0.1 --simulator advection-diffusion ";
  for (const char* k : {"0", "1"}) {
    const Result r = run(common + "--shard " + k + "/2 --out " + at(std::string("p") + k));
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const Result twice = run("dataset merge " + at("p0") + " " + at("p0") + " --out " + at("m"));
  EXPECT_EQ(twice.code, 2);
  EXPECT_TRUE(has(twice.err, "is given twice")) << twice.err;
  EXPECT_TRUE(has(twice.err, "argument 1") && has(twice.err, "argument 2")) << twice.err;
  EXPECT_FALSE(has(twice.err, "missing")) << twice.err;
  fs::copy(at("p0"), at("p0-copy"), fs::copy_options::recursive);
  const Result copy =
      run("dataset merge " + at("p0") + " " + at("p0-copy") + " " + at("p1") + " --out " + at("m"));
  EXPECT_EQ(copy.code, 2);
  EXPECT_TRUE(has(copy.err, "part 0 of 2 is given twice")) << copy.err;
  EXPECT_TRUE(has(copy.err, at("p0-copy"))) << copy.err;

  // Part 1's manifest claims 2 samples for its one-sample shard (the total agrees, so the
  // manifest itself parses).
  const std::string manifest = at("p1/manifest.part-1-of-2.json");
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(slurp(manifest));
  j["shards"][0]["samples"] = 2;
  j["samples"] = 2;
  std::ofstream(manifest) << j.dump(2) << "\n";
  const Result count = run("dataset merge " + at("p0") + " " + at("p1") + " --out " + at("m"));
  EXPECT_EQ(count.code, 2);
  EXPECT_TRUE(has(count.err, "part 1 of 2")) << count.err;
  EXPECT_TRUE(has(count.err, "shard-00001")) << count.err;
  EXPECT_TRUE(has(count.err, "2 samples") && has(count.err, "holds 1")) << count.err;
  EXPECT_FALSE(fs::exists(at("m")));
}

TEST_F(DatasetCli, ShowReportsTheSampleAndRefusesAnIndexBeyondTheDataset) {
  ASSERT_EQ(run("dataset generate --maps 1 --sources 2 --cell 0.1 --simulator "
                "advection-diffusion --out " +
                at("d"))
                .code,
            0);
  const Result r = run("dataset show " + at("d") + " --index 1 --json --out " + at("s.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["shard"], "shard-00000");
  EXPECT_EQ(j["row"], 1);
  EXPECT_EQ(j["inputs_sha256"].get<std::string>().size(), 64u);
  const Result beyond = run("dataset show " + at("d") + " --index 2 --out " + at("t.png"));
  EXPECT_EQ(beyond.code, 2);
  EXPECT_TRUE(has(beyond.err, "--index")) << beyond.err;
  EXPECT_TRUE(has(beyond.err, "2 samples")) << beyond.err;
}

TEST_F(DatasetCli, PredictTakesThePositionalMapAndCnnAndTheOldSpellings) {
  const Result now = run("predict " + kMap + " --cnn " + kCnn + " --source 1,1 --out " + at("a"));
  ASSERT_EQ(now.code, 0) << now.err;
  const Result old =
      run("predict --map " + kMap + " --model " + kCnn + " --source 1,1 -j 2 --out " + at("b"));
  ASSERT_EQ(old.code, 0) << old.err;
  EXPECT_TRUE(has(old.err, "--map is deprecated")) << old.err;
  EXPECT_TRUE(has(old.err, "--model is deprecated")) << old.err;
  EXPECT_TRUE(same_file(at("a/mean.npy"), at("b/mean.npy")));
  EXPECT_TRUE(same_file(at("a/std.npy"), at("b/std.npy")));
}

}  // namespace
