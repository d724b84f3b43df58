// The dataset's own files are read back through one validating reader: a damaged manifest.json,
// parameters.json, checksums.json or shard is exit 2 naming the file, the key and the fault, and
// leaves the dataset as it was; a resumed run with other parameters names each one and both
// values; a damaged wind cache is solved again; no provenance field holds an absolute path.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"
#include "dataset/dataset_reader.hpp"
#include "dataset/generator.hpp"
#include "support/cli_runner.hpp"

namespace plumekit::dataset {
namespace {

namespace fs = std::filesystem;
using test::CliResult;

// Every file under `dir` (relative path -> bytes).
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = read_file(e.path());
  return out;
}

void overwrite(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

const std::string kGenerate =
    "dataset generate --maps 1 --sources 2 --seed 7 --cell 0.1 --simulator advection-diffusion ";

class DatasetReader : public test::CliTest {
 protected:
  // One small dataset made once, copied for each test.
  static fs::path made() {
    static const fs::path d = [] {
      const fs::path p =
          fs::temp_directory_path() / ("plumekit-dataset-reader-" + std::to_string(::getpid()));
      fs::remove_all(p);
      const std::string cmd =
          std::string(PLUMEKIT_EXE) + " " + kGenerate + "--out " + p.string() + " > /dev/null";
      EXPECT_EQ(std::system(cmd.c_str()), 0);
      return p;
    }();
    return d;
  }
  static void TearDownTestSuite() { fs::remove_all(made()); }

  fs::path data;
  void SetUp() override {
    CliTest::SetUp();
    data = dir / "data";
    fs::copy(made(), data, fs::copy_options::recursive);
  }

  std::string expect_refused(const std::string& args, const std::string& needle) {
    const auto before = tree(data);
    const CliResult r = run(args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(tree(data), before) << "the dataset changed";
    return r.err;
  }
  std::string show() {
    return "dataset show " + data.string() + " --index 1 --out " + (dir / "s.png").string();
  }
};

std::string refusal(const std::string& bytes) {
  try {
    parse_manifest(bytes, "d/manifest.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST_F(DatasetReader, ManifestFaultsNameTheFileTheKeyAndTheFault) {
  const std::string good = read_file(data / "manifest.json");
  const Manifest m = parse_manifest(good, "d/manifest.json");
  EXPECT_EQ(m.maps, 1);
  EXPECT_EQ(m.samples, 2);
  ASSERT_EQ(m.shards.size(), 1u);
  EXPECT_EQ(m.shards[0].name, "shard-00000");

  EXPECT_NE(refusal(good.substr(0, good.size() / 2)).find("d/manifest.json: not valid JSON"),
            std::string::npos);
  const auto with = [&](const std::function<void(nlohmann::ordered_json&)>& change) {
    auto j = nlohmann::ordered_json::parse(good);
    change(j);
    return refusal(j.dump());
  };
  EXPECT_NE(with([](auto& j) {
              j["shards"][0]["samples"] = "2";
            }).find("d/manifest.json: shards[0].samples: expected an integer, found \"2\""),
            std::string::npos);
  EXPECT_NE(with([](auto& j) {
              j["shards"][0]["name"] = "../../etc";
            }).find("shards[0].name: \"../../etc\", expected \"shard-00000\""),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["shards"][0]["map"] = "/etc/passwd"; }).find("shards[0].map"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) {
              j["shards"][0]["map_index"] = 5;
            }).find("shards[0].map_index: 5 is outside 0..0"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) {
              j["shards"][0]["sha256"]["targets.npy"] = "xyz";
            }).find("shards[0].sha256.targets.npy: expected 64 lowercase hex digits"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["samples"] = 3; }).find("samples: 3, but the shards hold 2"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["format"] = "plumekit-dataset/9"; }).find("format"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) { j["generator"].erase("maps"); }).find("generator.maps: missing"),
            std::string::npos);
  EXPECT_NE(with([](auto& j) {
              j["generator"]["maps"] = 2000000000;
            }).find("generator.maps: 2000000000 is outside"),
            std::string::npos);
  EXPECT_NE(refusal("[]").find("expected a JSON object"), std::string::npos);
  EXPECT_NE(refusal("").find("not valid JSON"), std::string::npos);
}

// Random damage anywhere in a manifest is InputError or a manifest, never another exception or a
// crash (what the fuzz target checks at length).
// Found by fuzz_manifest: a number beyond a double escaped as nlohmann's out_of_range (exit 1).
TEST_F(DatasetReader, ANumberTooLargeForADoubleIsInputError) {
  for (const char* text : {R"({"samples": 1e400})", R"([1e400])"}) {
    try {
      parse_manifest(text, "d/manifest.json");
      ADD_FAILURE() << text << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("d/manifest.json"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse_parameters(text, "d/parameters.json"), InputError);
  }
}

TEST_F(DatasetReader, DamagedManifestBytesAreRefusedCleanly) {
  const std::string good = read_file(data / "manifest.json");
  std::mt19937 rng(5);
  int refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string bytes = good;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % bytes.size();
      switch (rng() % 3) {
        case 0:
          bytes[at] = static_cast<char>(rng());
          break;
        case 1:
          bytes.erase(at, 1 + rng() % 8);
          break;
        default:
          bytes.insert(at, 1, "0123456789-.e\"{}[],:"[rng() % 20]);
          break;
      }
      if (bytes.empty()) bytes = "x";
    }
    try {
      parse_manifest(bytes, "m.json");
    } catch (const InputError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind("m.json: ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(refused, 2000);
}

TEST_F(DatasetReader, TruncatedManifestIsExitTwoNamingIt) {
  const std::string m = read_file(data / "manifest.json");
  overwrite(data / "manifest.json", m.substr(0, m.size() / 2));
  expect_refused(show(), (data / "manifest.json").string() + ": not valid JSON");
  EXPECT_FALSE(fs::exists(dir / "s.png"));
}

TEST_F(DatasetReader, TruncatedParametersIsExitTwoNamingItAndTheDatasetStaysAsItWas) {
  const std::string p = read_file(data / "parameters.json");
  overwrite(data / "parameters.json", p.substr(0, p.size() - 40));
  const std::string err = expect_refused(kGenerate + "--out " + data.string(),
                                         (data / "parameters.json").string() + ": not valid JSON");
  EXPECT_NE(err.find("manifest.json"), std::string::npos) << err;  // says how to restore it
}

TEST_F(DatasetReader, ShowVerifiesTheShardItDraws) {
  const fs::path shard = data / "shards" / "shard-00000";
  const std::string targets = read_file(shard / "targets.npy");
  std::string flipped = targets;
  flipped[flipped.size() - 5] ^= 0x01;
  overwrite(shard / "targets.npy", flipped);
  expect_refused(show(), (shard / "targets.npy").string() + ": checksum mismatch");
  EXPECT_FALSE(fs::exists(dir / "s.png"));

  // checksums.json rewritten to match the changed file: the manifest's checksum still catches it.
  auto sums = nlohmann::ordered_json::parse(read_file(shard / "checksums.json"));
  sums["targets.npy"] = sha256_hex(flipped);
  overwrite(shard / "checksums.json", sums.dump(2));
  expect_refused(show(), (shard / "checksums.json").string() +
                             ": targets.npy: differs from the dataset's manifest");
  overwrite(shard / "checksums.json", "{");
  expect_refused(show(), (shard / "checksums.json").string() + ": not valid JSON");

  // Restored, it draws.
  fs::remove_all(data);
  fs::copy(made(), data, fs::copy_options::recursive);
  const CliResult r = run(show());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "s.png"));
}

TEST_F(DatasetReader, ResumeWithOtherParametersNamesEachWithBothValues) {
  std::string err = expect_refused(
      "dataset generate --maps 1 --sources 2 --seed 7 --cell 0.1 --simulator advection-diffusion "
      "--release-rate 500 --out " +
          data.string(),
      "advection_diffusion.release_rate: this run 500.0, the dataset 1000.0");
  EXPECT_EQ(err.find("seed:"), std::string::npos) << err;  // only what differs
  err = expect_refused(
      "dataset generate --maps 1 --sources 3 --seed 8 --cell 0.1 --simulator advection-diffusion "
      "--out " +
          data.string(),
      "seed: this run 8, the dataset 7");
  EXPECT_NE(err.find("sources_per_map: this run 3, the dataset 2"), std::string::npos) << err;
  // The same parameters resume (nothing to redo).
  const CliResult r = run(kGenerate + "--out " + data.string() + " --json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"maps_resumed\": 1"), std::string::npos) << r.out;
}

TEST_F(DatasetReader, ParameterDifferencesListAddedAndRemovedKeys) {
  const nlohmann::json a = {{"seed", 1}, {"flow", {{"cell", 0.05}, {"nu", 0.01}}}, {"x", true}};
  const nlohmann::json b = {{"seed", 1}, {"flow", {{"cell", 0.1}, {"nu", 0.01}}}, {"y", "u"}};
  const std::vector<std::string> d = parameter_differences(a, b);
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0], "flow.cell: this run 0.05, the dataset 0.1");
  EXPECT_EQ(d[1], "x: this run true, the dataset none");
  EXPECT_EQ(d[2], "y: this run none, the dataset \"u\"");
  EXPECT_TRUE(parameter_differences(a, a).empty());
}

TEST_F(DatasetReader, ADamagedWindCacheIsSolvedAgain) {
  const auto whole = tree(data);
  const fs::path face_u = data / "wind" / "map-00000" / "face_u.npy";
  std::string bytes = read_file(face_u);
  bytes[bytes.size() - 3] ^= 0x7f;  // a wrong wind, not a broken file
  overwrite(face_u, bytes);
  fs::remove_all(data / "shards" / "shard-00000");
  CliResult r = run(kGenerate + "--out " + data.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"winds_cached\": 0"), std::string::npos) << r.out;
  EXPECT_EQ(tree(data), whole);
  // An intact cache is used.
  fs::remove_all(data / "shards" / "shard-00000");
  r = run(kGenerate + "--out " + data.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"winds_cached\": 1"), std::string::npos) << r.out;
  EXPECT_EQ(tree(data), whole);
}

// Every string in a JSON document.
void strings(const nlohmann::json& j, std::vector<std::string>& out) {
  if (j.is_string()) out.push_back(j.get<std::string>());
  if (j.is_structured())
    for (const auto& v : j)
      strings(v, out);
}

TEST_F(DatasetReader, ProvenanceHoldsNoAbsolutePaths) {
  const fs::path maps = dir / "maps-in";
  fs::create_directories(maps);
  std::ofstream(maps / "one.json") << R"({
  "format": "plumekit-map/1", "name": "one", "size": [10.0, 4.0],
  "inlet": {"side": "left", "speed": 1.0}, "outlet": {"side": "right"},
  "obstacles": [[[4.0, 1.0], [5.0, 1.0], [5.0, 2.0], [4.0, 2.0]]],
  "sources": [[7.0, 2.5]]})";
  const fs::path out = dir / "given";
  const CliResult r = run("dataset generate --cell 0.1 --simulator advection-diffusion --map-dir " +
                          fs::absolute(maps).string() + " --out " + fs::absolute(out).string());
  ASSERT_EQ(r.code, 0) << r.err;
  for (const fs::path& f :
       {out / "manifest.json", out / "parameters.json", out / "wind" / "map-00000" / "wind.json",
        data / "manifest.json", data / "wind" / "map-00000" / "wind.json"}) {
    std::vector<std::string> all;
    strings(nlohmann::json::parse(read_file(f)), all);
    for (const std::string& s : all)
      EXPECT_TRUE(s.empty() || s[0] != '/') << f << " holds " << s;
  }
  EXPECT_NE(read_file(out / "manifest.json").find("\"one.json\""), std::string::npos);
}

// read_sample walks the manifest's shards: the sample's row, source and channels are the shard's,
// and an index beyond the dataset names the option field.
TEST_F(DatasetReader, ReadSampleReturnsTheShardsRow) {
  const DatasetSample s = read_sample(data, 1);
  EXPECT_EQ(s.shard.name, "shard-00000");
  EXPECT_EQ(s.row, 1);
  const Manifest m = read_manifest(data / "manifest.json");
  const ShardArrays a = read_shard(data, m.shards.at(0), 3);
  EXPECT_EQ(s.source.x, a.sources[2]);
  EXPECT_EQ(s.source.y, a.sources[3]);
  ASSERT_EQ(s.inputs.size(), 3u);
  ASSERT_EQ(s.targets.size(), 2u);
  const std::size_t plane = 64 * 64;
  EXPECT_EQ(s.targets[1].values[7], a.targets[(1 * 2 + 1) * plane + 7]);
  EXPECT_EQ(s.inputs[2].values[9], a.inputs[(1 * 3 + 2) * plane + 9]);
  EXPECT_EQ(s.inputs_sha256.size(), 64u);
  EXPECT_NE(s.inputs_sha256, read_sample(data, 0).inputs_sha256);
  try {
    read_sample(data, 2);
    ADD_FAILURE() << "no OptionError";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "show.index");
  }
}

// Parameters written before issue 15 say filament.record_seconds; they read as record_s, in
// place, so the dataset resumes with today's parameters.
TEST(DatasetParameters, OlderRecordSecondsKeyReadsAsRecordS) {
  const std::string old = R"({"seed": 1, "maps": 2, "filament": {"dt": 0.05,
    "record_seconds": 5.0, "sample_rate": 10.0}})";
  const nlohmann::ordered_json p = parse_parameters(old, "parameters.json");
  const nlohmann::ordered_json& f = p.at("filament");
  EXPECT_FALSE(f.contains("record_seconds"));
  EXPECT_EQ(f.at("record_s"), 5.0);
  EXPECT_EQ(f.dump(), R"({"dt":0.05,"record_s":5.0,"sample_rate":10.0})");
  const nlohmann::ordered_json now = nlohmann::ordered_json::parse(
      R"({"seed": 1, "maps": 2, "filament": {"dt": 0.05, "record_s": 5.0, "sample_rate": 10.0}})");
  EXPECT_TRUE(parameter_differences(now, p).empty());
}

}  // namespace
}  // namespace plumekit::dataset
