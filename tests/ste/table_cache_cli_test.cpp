// `localize --table-cache` from the command line: a file named as the cache folder is exit 2
// naming it (and left alone); a damaged cache is rebuilt with a note and the same estimate.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"

namespace plumekit::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

class TableCacheCli : public CliTest {
 protected:
  // A short surrogate run with the committed random-weight model on a shipped 10 x 4 m map.
  CliResult localize(const fs::path& cache) {
    return run("localize " +
               (fs::path(PLUMEKIT_DATA_DIR) / "test-maps" / "test-1-block.json").string() +
               " --source 8.5,1 --start 1,2 --plume-model surrogate --cnn " +
               (fs::path(PLUMEKIT_TEST_DATA) / "surrogate" / "real.pkcnn").string() +
               " --source-cell 1 --max-samples 3 --seed 5 --json --table-cache " + cache.string());
  }
};

TEST_F(TableCacheCli, AFileAsTheCacheIsExitTwoNamingItAndLeftAlone) {
  const fs::path file = dir / "thesis.pdf";
  std::ofstream(file) << "not a cache";
  const CliResult r = localize(file);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(file.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not a folder"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(file), "not a cache");
}

TEST_F(TableCacheCli, AFlippedByteIsRebuiltWithANoteAndTheSameEstimate) {
  const fs::path cache = dir / "cache";
  const CliResult first = localize(cache);
  ASSERT_EQ(first.code, 0) << first.err;
  fs::path table;
  for (const auto& e : fs::directory_iterator(cache))
    table = e.path();
  ASSERT_FALSE(table.empty());
  std::string bytes = slurp(table);
  bytes[bytes.size() / 2] ^= 0x10;
  std::ofstream(table, std::ios::binary | std::ios::trunc) << bytes;

  const CliResult again = localize(cache);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("note: table cache"), std::string::npos) << again.err;
  EXPECT_NE(again.err.find("checksum mismatch"), std::string::npos) << again.err;
  const json a = json::parse(first.out), b = json::parse(again.out);
  EXPECT_EQ(a["estimate"], b["estimate"]);
  EXPECT_TRUE(std::isfinite(b["estimate"][0].get<double>()));
}

}  // namespace
}  // namespace plumekit::test
