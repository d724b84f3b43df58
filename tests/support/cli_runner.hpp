#pragma once
// Runs the plumekit program (PLUMEKIT_EXE) from a test, in a temporary
// directory of the test's own, and captures its exit code and output.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace plumekit::test {

struct CliResult {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class CliTest : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() / test_name();

  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }

  // Runs `plumekit ARGS` with stdout and stderr captured; the capture files
  // are removed again so that the test directory holds only what the program wrote.
  CliResult run(const std::string& args) {
    const std::filesystem::path out = dir / "stdout", err = dir / "stderr";
    const std::string cmd =
        std::string(PLUMEKIT_EXE) + " " + args + " >" + out.string() + " 2>" + err.string();
    const int status = std::system(cmd.c_str());
    CliResult r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
  }

 private:
  static std::string test_name() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // The process id keeps two suites running at once (two build trees) out of each other's way.
    return std::string("plumekit_") + info->test_suite_name() + "_" + info->name() + "_" +
           std::to_string(getpid());
  }
};

}  // namespace plumekit::test
