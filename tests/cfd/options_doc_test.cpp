// docs/options.md is made from the options tables: it must be exactly what
// `plumekit options --markdown` prints, and its defaults the structs' own.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "cfd/options.hpp"
#include "support/cli_runner.hpp"

namespace {

std::string read_doc() {
  std::ifstream in(std::string(plumekit_test_paths::source_dir()) + "/docs/options.md");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class OptionsDoc : public plumekit::test::CliTest {};

TEST_F(OptionsDoc, MatchesTheCode) {
  const auto r = run("options --markdown");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.out == read_doc())
      << "docs/options.md differs from what the code generates; regenerate it with\n"
         "  build/plumekit options --markdown > docs/options.md\n"
         "(from the source folder, after building the plumekit target) and commit it.";
}

// The default column of every flow option is the default of a fresh FlowOptions.
TEST(OptionsDocDefaults, AreTheFlowOptionsDefaults) {
  const std::string doc = read_doc();
  const plumekit::cfd::FlowOptions fresh;
  for (const auto& e : plumekit::cfd::flow_option_table().entries) {
    const std::size_t row = doc.find("| `" + e.name + "` |");
    ASSERT_NE(row, std::string::npos) << e.name << " not in docs/options.md";
    const std::string line = doc.substr(row, doc.find('\n', row) - row);
    EXPECT_NE(line.find("| `" + plumekit::value_text(e, fresh) + "` |"), std::string::npos) << line;
  }
  // And read back as a number, the viscosity's is the struct's.
  const std::size_t row = doc.find("| `flow.nu` |");
  const std::size_t at = doc.find("| `", row + 5);
  const std::size_t value = doc.find('`', doc.find("| `", at + 3) + 1);
  EXPECT_EQ(std::stod(doc.substr(value + 1)), fresh.nu);
}

}  // namespace
