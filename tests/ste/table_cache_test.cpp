// The surrogate table cache is checked before use: a damaged file is rebuilt with a note and gives
// the answer a fresh build gives; a cache path that cannot hold the cache is refused before the
// table is built; files that are not the cache's own are never touched.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"
#include "map/map_json.hpp"
#include "ste/surrogate_plume.hpp"

namespace plumekit::ste {
namespace {

namespace fs = std::filesystem;

const fs::path kRandomModel = fs::path(PLUMEKIT_TEST_DATA) / "surrogate" / "real.pkcnn";

class TableCache : public ::testing::Test {
 protected:
  fs::path dir =
      fs::temp_directory_path() / ("plumekit-table-cache-" + std::to_string(::getpid()) + "-" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  Map map = read_map(fs::path(PLUMEKIT_DATA_DIR) / "test-maps" / "test-1-block.json");
  std::vector<std::string> notes;

  void SetUp() override { fs::remove_all(dir); }
  void TearDown() override { fs::remove_all(dir); }

  SurrogatePlumeOptions options(const fs::path& cache) {
    SurrogatePlumeOptions o;
    o.model = kRandomModel;
    o.source_cell = 1.0;  // 10 x 4 cells: quick, also under the sanitizers
    o.cache_dir = cache;
    o.on_note = [this](const std::string& n) { notes.push_back(n); };
    return o;
  }

  // Every reading and spread of every source at a few points.
  static std::vector<double> answers(const SurrogatePlume& m) {
    std::vector<double> out;
    for (Vec2 p : {Vec2{6.1, 2.9}, Vec2{8.3, 0.7}, Vec2{1.2, 3.1}}) {
      const std::vector<double> r = m.readings_at(p), s = m.spreads_at(p);
      out.insert(out.end(), r.begin(), r.end());
      out.insert(out.end(), s.begin(), s.end());
    }
    return out;
  }

  // Damages the one cache file with `damage`, then expects a rebuild with a note naming the file
  // and `fault`, the fresh answer, and a cache that is good again.
  void expect_rebuilt(const std::function<void(std::string&)>& damage, const std::string& fault) {
    const SurrogatePlume fresh(map, options(dir));
    ASSERT_FALSE(fresh.from_cache());
    const fs::path file = fresh.cache_file();
    std::string bytes = read_file(file);
    damage(bytes);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;

    const SurrogatePlume rebuilt(map, options(dir));
    EXPECT_FALSE(rebuilt.from_cache());
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find(file.string()), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find(fault), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("rebuilding"), std::string::npos) << notes[0];
    EXPECT_EQ(rebuilt.cache_rebuilt_because().empty(), false);
    EXPECT_EQ(answers(rebuilt), answers(fresh));

    const SurrogatePlume again(map, options(dir));
    EXPECT_TRUE(again.from_cache());
    EXPECT_EQ(answers(again), answers(fresh));
    EXPECT_EQ(notes.size(), 1u);
  }
};

TEST_F(TableCache, FlippedByteIsRebuiltWithANoteAndTheFreshAnswer) {
  expect_rebuilt([](std::string& b) { b[b.size() / 2] ^= 0x40; }, "checksum mismatch");
}

TEST_F(TableCache, ZeroedFileIsRebuiltWithANoteAndTheFreshAnswer) {
  expect_rebuilt([](std::string& b) { b.assign(b.size(), '\0'); }, "not a surrogate table cache");
}

TEST_F(TableCache, TruncatedFileIsRebuiltWithANoteAndTheFreshAnswer) {
  expect_rebuilt([](std::string& b) { b.resize(b.size() - 100); }, "checksum mismatch");
}

TEST_F(TableCache, OlderFormatIsRebuilt) {
  expect_rebuilt([](std::string& b) { b[6] = '2'; }, "older or unknown table cache format");
}

TEST_F(TableCache, ParseRefusesNonFiniteValuesAndInconsistentSizesEvenWithAGoodChecksum) {
  SurrogateTable t;
  t.key = std::string(64, 'a');
  t.rows = 2;
  t.per = 3;
  t.mean = {0, 1, 2, 3, 4, 5};
  t.std = {0, 0, 0, 0, 0, 0};
  const SurrogateTable back = parse_table_cache(table_cache_bytes(t), "x.bin");
  EXPECT_EQ(back.key, t.key);
  EXPECT_EQ(back.mean, t.mean);
  EXPECT_EQ(back.std, t.std);

  const auto message = [](const SurrogateTable& bad) {
    try {
      parse_table_cache(table_cache_bytes(bad), "cache/x.bin");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  SurrogateTable nan = t;
  nan.mean[4] = std::nanf("");
  EXPECT_NE(message(nan).find("cache/x.bin: mean plume 1 cell 1"), std::string::npos)
      << message(nan);
  SurrogateTable negative = t;
  negative.std[0] = -1.0f;
  EXPECT_NE(message(negative).find("std plume 0 cell 0"), std::string::npos);
  SurrogateTable sizes = t;
  sizes.rows = 3;  // claims more than it holds
  EXPECT_NE(message(sizes).find("do not hold 2 x 3 rows x 3"), std::string::npos) << message(sizes);
  SurrogateTable huge = t;
  huge.rows = huge.per = 0xFFFFFFFFu;  // no allocation follows a damaged size
  EXPECT_NE(message(huge).find("do not hold"), std::string::npos);
  EXPECT_THROW(parse_table_cache("", "x"), InputError);
  EXPECT_THROW(parse_table_cache(std::string(100, 'P'), "x"), InputError);
}

// Damage with a recomputed checksum (what a fuzz target reaches): any byte of the header or the
// plumes, or a cut, is InputError or a table whose sizes fit its bytes, never a crash.
// Found by fuzz_table_cache: copying the plumes of an empty table was undefined behaviour.
TEST_F(TableCache, AnEmptyTableReadsBack) {
  SurrogateTable t;
  t.key = std::string(64, 'b');
  t.per = 4;
  const SurrogateTable back = parse_table_cache(table_cache_bytes(t), "empty.bin");
  EXPECT_EQ(back.rows, 0u);
  EXPECT_TRUE(back.mean.empty());
  EXPECT_TRUE(back.std.empty());
}

TEST_F(TableCache, ParseSurvivesDamageBehindAGoodChecksum) {
  SurrogateTable t;
  t.key = std::string(64, 'b');
  t.rows = 3;
  t.per = 4;
  t.mean.assign(12, 1.5f);
  t.std.assign(12, 0.5f);
  const std::string good = table_cache_bytes(t);
  std::mt19937 rng(9);
  int refused = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    std::string body = good.substr(0, good.size() - 32);
    const std::size_t at = rng() % body.size();
    if (trial % 5 == 0)
      body.resize(at);
    else
      body[at] = static_cast<char>(rng());
    const Sha256Digest d = sha256(body);
    const std::string bytes = body + std::string(reinterpret_cast<const char*>(d.data()), 32);
    try {
      const SurrogateTable back = parse_table_cache(bytes, "t.bin");
      EXPECT_EQ(back.mean.size(), std::size_t{back.rows} * back.per);
      EXPECT_EQ(back.std.size(), back.mean.size());
    } catch (const InputError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).rfind("t.bin: ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(refused, 1000);
}

TEST_F(TableCache, AFileAsTheCacheFolderIsRefusedAndLeftAlone) {
  fs::create_directories(dir);
  const fs::path file = dir / "notes.txt";
  std::ofstream(file) << "my notes";
  try {
    SurrogatePlume m(map, options(file));
    FAIL() << "accepted a file as the cache folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ": exists and is not a folder"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read_file(file), "my notes");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST_F(TableCache, AnUnwritableFolderIsRefusedBeforeTheTableIsBuilt) {
  // /proc exists and takes no new files, even for root (who ignores permission bits).
  SurrogatePlumeOptions o = options("/proc");
  o.source_cell = 0.05;  // 200 x 80 candidate sources: minutes to build, so a quick
                         // refusal shows the check comes first
  const auto t0 = std::chrono::steady_clock::now();
  try {
    SurrogatePlume m(map, o);
    FAIL() << "accepted an unwritable cache folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("table cache /proc: cannot write in this folder"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  // A cache folder under a file cannot be created.
  fs::create_directories(dir);
  std::ofstream(dir / "plain") << "x";
  EXPECT_THROW(SurrogatePlume(map, options(dir / "plain" / "cache")), InputError);
}

TEST_F(TableCache, ForeignFilesInTheCacheFolderAreNeverTouched) {
  fs::create_directories(dir);
  const std::map<std::string, std::string> foreign{
      {"thesis.tex", "chapter 1"},
      {"surrogate-table-notes.txt", "not a table"},
      {"surrogate-table.bin", "also not ours: no key"}};
  for (const auto& [name, text] : foreign)
    std::ofstream(dir / name) << text;
  const SurrogatePlume built(map, options(dir));
  std::string bytes = read_file(built.cache_file());
  bytes[bytes.size() / 3] ^= 1;
  std::ofstream(built.cache_file(), std::ios::binary | std::ios::trunc) << bytes;
  const SurrogatePlume rebuilt(map, options(dir));  // rewrites its own file only
  EXPECT_FALSE(rebuilt.from_cache());
  for (const auto& [name, text] : foreign)
    EXPECT_EQ(read_file(dir / name), text) << name;
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++files;
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(foreign.count(name) || e.path() == built.cache_file()) << name;
  }
  EXPECT_EQ(files, 4);
}

}  // namespace
}  // namespace plumekit::ste
