// The output rule (core/output_target.hpp): what may be written where, and
// that nothing plumekit did not write is ever removed or replaced.
#include "core/output_target.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/temporary_files.hpp"
#include "support/files.hpp"

namespace plumekit {
namespace {

namespace fs = std::filesystem;

const auto& slurp = test::file_bytes;
const auto& put = test::put_file;
using test::snapshot;

template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class OutputTargetTest : public ::testing::Test {
 protected:
  fs::path dir =
      fs::temp_directory_path() / ("plumekit-output-" + std::to_string(::getpid()) + "-" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::path old_cwd = fs::current_path();
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::current_path(dir);
  }
  void TearDown() override {
    fs::current_path(old_cwd);
    fs::remove_all(dir);
  }
  void write_run(const fs::path& target, const std::string& command, const std::string& text) {
    OutputDirectory out(target, command);
    put(out.open() / "result.txt", text);
    put(out.open() / "sub" / "deep.txt", text);
    out.commit();
  }
};

TEST_F(OutputTargetTest, NewFolderAppearsWithMarkerAndFiles) {
  write_run("a/b/run", "evaluate", "one");
  EXPECT_EQ(slurp("a/b/run/result.txt"), "one");
  EXPECT_EQ(slurp("a/b/run/sub/deep.txt"), "one");
  EXPECT_TRUE(fs::exists("a/b/run/.plumekit-output.json"));
  // nothing else beside it
  EXPECT_EQ(std::distance(fs::directory_iterator("a/b"), fs::directory_iterator{}), 1);
}

TEST_F(OutputTargetTest, OwnEarlierOutputIsReplaced) {
  write_run("run", "evaluate", "one");
  write_run("run", "evaluate", "two");
  EXPECT_EQ(slurp("run/result.txt"), "two");
  EXPECT_EQ(std::distance(fs::directory_iterator("."), fs::directory_iterator{}), 1);
}

TEST_F(OutputTargetTest, EmptyFolderIsUsed) {
  fs::create_directory("empty");
  write_run("empty", "flow", "x");
  EXPECT_EQ(slurp("empty/result.txt"), "x");
}

TEST_F(OutputTargetTest, FolderWithForeignFilesIsRefusedUntouched) {
  put("thesis/thesis.tex", "years of work");
  put("thesis/data/run.csv", "1,2,3");
  const auto before = snapshot("thesis");
  const std::string e = input_error([&] { OutputDirectory out("thesis", "evaluate"); });
  EXPECT_NE(e.find("thesis: holds files plumekit did not write"), std::string::npos) << e;
  EXPECT_NE(e.find("thesis.tex"), std::string::npos) << e;
  EXPECT_EQ(snapshot("thesis"), before);
}

TEST_F(OutputTargetTest, OwnOutputWithAnAddedFileIsRefused) {
  write_run("run", "evaluate", "one");
  put("run/notes.txt", "mine");
  const std::string e = input_error([&] { OutputDirectory out("run", "evaluate"); });
  EXPECT_NE(e.find("notes.txt"), std::string::npos) << e;
  EXPECT_EQ(slurp("run/notes.txt"), "mine");
}

TEST_F(OutputTargetTest, AnotherCommandsOutputIsRefused) {
  write_run("run", "flow", "one");
  const std::string e = input_error([&] { OutputDirectory out("run", "evaluate"); });
  EXPECT_NE(e.find("holds the output of `plumekit flow`"), std::string::npos) << e;
}

TEST_F(OutputTargetTest, CurrentFolderAndItsParentsAreRefused) {
  put("keep.txt", "x");
  EXPECT_NE(input_error([&] { OutputDirectory out(".", "evaluate"); }).find("the current folder"),
            std::string::npos);
  EXPECT_NE(input_error([&] {
              OutputDirectory out("..", "evaluate");
            }).find("a folder holding the current folder"),
            std::string::npos);
  EXPECT_NE(input_error([&] { OutputDirectory out(dir, "evaluate"); }).find("current folder"),
            std::string::npos);
  EXPECT_EQ(slurp("keep.txt"), "x");
}

TEST_F(OutputTargetTest, InputsAreRefusedEitherWay) {
  put("maps/a.json", "{}");
  EXPECT_NE(input_error([&] {
              OutputDirectory out("maps", "evaluate", {"maps"});
            }).find("is also an input"),
            std::string::npos);
  EXPECT_NE(input_error([&] {
              OutputDirectory out("maps/out", "evaluate", {"maps"});
            }).find("lies inside the input maps"),
            std::string::npos);
  EXPECT_NE(input_error([&] { OutputDirectory out(".", "evaluate", {"maps/a.json"}); }).size(), 0u);
  EXPECT_NE(input_error([&] {
              check_output_file("maps/a.json", {"maps/a.json"});
            }).find("is also an input"),
            std::string::npos);
  EXPECT_EQ(slurp("maps/a.json"), "{}");
}

TEST_F(OutputTargetTest, FileForFolderAndFolderForFileAreRefused) {
  put("file.txt", "mine");
  EXPECT_NE(input_error([&] { OutputDirectory out("file.txt", "flow"); }).find("is a file"),
            std::string::npos);
  EXPECT_NE(input_error([&] { OutputDirectory out("file.txt/sub", "flow"); }).find("is a file"),
            std::string::npos);
  fs::create_directory("folder.png");
  EXPECT_NE(input_error([&] { check_output_file("folder.png"); }).find("is a folder"),
            std::string::npos);
  EXPECT_EQ(slurp("file.txt"), "mine");
}

TEST_F(OutputTargetTest, UncommittedFolderLeavesNothing) {
  {
    OutputDirectory out("new/deeper/run", "flow");
    put(out.open() / "half.txt", "x");
  }
  EXPECT_EQ(std::distance(fs::directory_iterator("."), fs::directory_iterator{}), 0);
}

TEST_F(OutputTargetTest, FilesAreOverwrittenOnlyWhenPlumekitWroteThem) {
  put("user.png", "\x89PNG\r\n\x1a\n not ours");
  const std::string e = input_error([&] { write_output_file("user.png", "new"); });
  EXPECT_NE(e.find("was not written by plumekit"), std::string::npos) << e;
  EXPECT_EQ(slurp("user.png"), "\x89PNG\r\n\x1a\n not ours");

  const std::string png = mark_png(encode_png(cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3))));
  write_output_file("ours.png", png);
  EXPECT_TRUE(written_by_plumekit("ours.png"));
  EXPECT_NO_THROW(write_output_file("ours.png", png));
  EXPECT_FALSE(written_by_plumekit("user.png"));
  // the marked PNG still decodes, with the same pixels
  const cv::Mat back = read_gray_image("ours.png");
  ASSERT_EQ(back.rows, 4);

  put("map.json",
      "{\"format\": \"plumekit-map/1\", \"generated_by\": \"plumekit map import-ros\"}");
  EXPECT_TRUE(written_by_plumekit("map.json"));
  put("hand.json", "{\"format\": \"plumekit-map/1\"}");
  EXPECT_FALSE(written_by_plumekit("hand.json"));
  put("empty.png", "");
  EXPECT_NO_THROW(check_output_file("empty.png"));
}

TEST_F(OutputTargetTest, StaleTemporariesOfDeadRunsAreRemovedOthersKept) {
  // A pid that cannot run: above the kernel's pid_max.
  fs::create_directories("run.plumekit-tmp-999999999-0/x");
  fs::create_directories("run.plumekit-tmp-" + std::to_string(::getpid()) + "-0");
  fs::create_directories("run.tmp-999999999-0");  // not our pattern
  fs::create_directories("other.plumekit-tmp-999999999-0");
  EXPECT_EQ(remove_stale_temporaries(dir / "run"), 1);
  EXPECT_FALSE(fs::exists("run.plumekit-tmp-999999999-0"));
  EXPECT_TRUE(fs::exists("run.plumekit-tmp-" + std::to_string(::getpid()) + "-0"));
  EXPECT_TRUE(fs::exists("run.tmp-999999999-0"));
  EXPECT_TRUE(fs::exists("other.plumekit-tmp-999999999-0"));
}

TEST_F(OutputTargetTest, SafeFileNamesFromFileContents) {
  std::vector<std::string> taken;
  EXPECT_EQ(safe_file_name("../../escaped", taken), "______escaped");
  EXPECT_EQ(safe_file_name("a/b", taken), "a_b");
  EXPECT_EQ(safe_file_name("a/b", taken), "a_b-2");
  EXPECT_EQ(safe_file_name("", taken), "unnamed");
  EXPECT_EQ(safe_file_name(".hidden", taken), "_hidden");
  EXPECT_EQ(safe_file_name(std::string("bell\a\n"), taken), "bell__");
  EXPECT_EQ(safe_file_name(std::string(300, 'x'), taken).size(), 80u);
}

TEST_F(OutputTargetTest, ProvenanceNeverRecordsAnAbsolutePath) {
  put("maps/a.json", "{}");
  EXPECT_EQ(provenance_path("maps/a.json"), "maps/a.json");
  EXPECT_EQ(provenance_path(dir / "maps" / "a.json"), "maps/a.json");
  EXPECT_EQ(provenance_path(dir / "maps"), "maps");
  EXPECT_EQ(provenance_path("/usr/share/somewhere/b.json"), "b.json");
  EXPECT_EQ(provenance_path("/usr/share/somewhere/"), "somewhere");
}

TEST_F(OutputTargetTest, InPlaceClaimAcceptsOwnLayoutOnly) {
  auto own = [](const std::string& n) { return n == "shards" || n == "parameters.json"; };
  EXPECT_FALSE(claim_output_directory("ds", "dataset generate", {"dataset generate"}, own,
                                      "parameters.json"));
  EXPECT_TRUE(fs::exists("ds/.plumekit-output.json"));
  put("ds/parameters.json", "{}");
  EXPECT_TRUE(claim_output_directory("ds", "dataset generate", {"dataset generate"}, own,
                                     "parameters.json"));
  put("ds/thesis.pdf", "x");
  EXPECT_NE(input_error([&] {
              claim_output_directory("ds", "dataset generate", {"dataset generate"}, own,
                                     "parameters.json");
            }).find("thesis.pdf"),
            std::string::npos);
  // a dataset from before markers: recognised by its parameters.json
  put("legacy/parameters.json", "{}");
  EXPECT_TRUE(claim_output_directory("legacy", "dataset generate", {"dataset generate"}, own,
                                     "parameters.json"));
  put("foreign/a.txt", "x");
  EXPECT_NE(input_error([&] {
              claim_output_directory("foreign", "dataset generate", {"dataset generate"}, own,
                                     "parameters.json");
            }).find("did not write"),
            std::string::npos);
  EXPECT_FALSE(fs::exists("foreign/.plumekit-output.json"));
}

}  // namespace
}  // namespace plumekit
