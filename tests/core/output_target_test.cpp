// The output rule (core/output_target.hpp): what may be written where, and
// that nothing plumekit did not write is ever removed or replaced.
#include "core/output_target.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/image_io.hpp"
#include "core/sha256.hpp"
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

// What a run killed outright leaves: a marked temporary folder (temporary_files.hpp) of a
// process id that cannot run (above the kernel's pid_max).
void put_stale_temporary(const std::string& name, const std::string& payload) {
  fs::create_directories(name + "/" + payload);
  put(name + "/" + payload + "/half.txt", "half");
  put(name + "/.plumekit-temporary", "plumekit-temporary/1\n" + name + "\n");
}

TEST_F(OutputTargetTest, StaleTemporariesOfDeadRunsAreRemovedOthersKept) {
  put_stale_temporary("run.plumekit-tmp-999999999-0", "run");
  // a live process's, another target's, and not our pattern
  put_stale_temporary("run.plumekit-tmp-" + std::to_string(::getpid()) + "-0", "run");
  put_stale_temporary("other.plumekit-tmp-999999999-0", "other");
  fs::create_directories("run.tmp-999999999-0");
  EXPECT_EQ(remove_stale_temporaries(dir / "run"), 1);
  EXPECT_FALSE(fs::exists("run.plumekit-tmp-999999999-0"));
  EXPECT_TRUE(fs::exists("run.plumekit-tmp-" + std::to_string(::getpid()) + "-0"));
  EXPECT_TRUE(fs::exists("run.tmp-999999999-0"));
  EXPECT_TRUE(fs::exists("other.plumekit-tmp-999999999-0"));
  EXPECT_EQ(remove_stale_temporaries_in(dir), 1);
  EXPECT_FALSE(fs::exists("other.plumekit-tmp-999999999-0"));
}

// Issue 44: a name alone never gets anything removed.
TEST_F(OutputTargetTest, LookAlikesOfTemporariesSurvive) {
  put("run.plumekit-tmp-999999999-1/thesis.tex", "years of work");  // no marker
  put("run.plumekit-tmp-999999999-2", "a file");
  put_stale_temporary("run.plumekit-tmp-999999999-3", "run");
  put("run.plumekit-tmp-999999999-3/.plumekit-temporary",
      "plumekit-temporary/1\nrun.plumekit-tmp-999999999-0\n");  // another folder's marker
  put_stale_temporary("run.plumekit-tmp-999999999-4", "run");
  put("run.plumekit-tmp-999999999-4/notes.txt", "added by hand");
  fs::create_directories("elsewhere");
  put_stale_temporary("elsewhere/run.plumekit-tmp-999999999-5", "run");
  fs::create_directory_symlink("elsewhere/run.plumekit-tmp-999999999-5",
                               "run.plumekit-tmp-999999999-5");
  const auto before = snapshot(".");
  EXPECT_EQ(remove_stale_temporaries(dir / "run"), 0);
  EXPECT_EQ(remove_stale_temporaries_in(dir), 0);
  write_run("run", "evaluate", "one");
  fs::remove_all("run");
  EXPECT_EQ(snapshot("."), before);
}

TEST_F(OutputTargetTest, TemporaryIsAMarkedFolderRemovedWithItsContents) {
  fs::path folder;
  {
    const Temporary t(dir / "out.npy");
    folder = t.folder();
    EXPECT_EQ(t.path(), folder / "out.npy");
    EXPECT_EQ(folder.parent_path(), dir);
    EXPECT_EQ(slurp(folder / ".plumekit-temporary"),
              "plumekit-temporary/1\n" + folder.filename().string() + "\n");
    put(t.path(), "x");
  }
  EXPECT_FALSE(fs::exists(folder));
  write_output_file("out.npy", "bytes");
  EXPECT_EQ(std::distance(fs::directory_iterator("."), fs::directory_iterator{}), 1);
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

// Issue 44: a marker lists each file with its size and SHA-256, so that one
// copied or edited to list a user's file never gets it deleted.
TEST_F(OutputTargetTest, MarkerBindsFilesBySizeAndHash) {
  write_run("run", "evaluate", "one");
  const auto marker = nlohmann::json::parse(slurp("run/.plumekit-output.json"));
  EXPECT_EQ(marker["format"], "plumekit-output/2");
  ASSERT_EQ(marker["files"].size(), 2u);
  EXPECT_EQ(marker["files"][0]["path"], "result.txt");
  EXPECT_EQ(marker["files"][0]["size"], 3);
  EXPECT_EQ(marker["files"][0]["sha256"], sha256_hex("one"));
  put("run/result.txt", "mine");  // rewritten by hand
  const auto before = snapshot("run");
  const std::string e = input_error([&] { OutputDirectory out("run", "evaluate"); });
  EXPECT_NE(e.find("run: result.txt is not the file plumekit wrote there"), std::string::npos) << e;
  EXPECT_EQ(snapshot("run"), before);
}

TEST_F(OutputTargetTest, ForgedOrOlderMarkersDoNotMakeFilesOurs) {
  put("thesis/thesis.tex", "years of work");
  put("thesis/.plumekit-output.json",
      R"({"format": "plumekit-output/1", "command": "evaluate", "files": ["thesis.tex"]})");
  put("copied/thesis.tex", "years of work");
  put("copied/.plumekit-output.json",
      R"({"format": "plumekit-output/2", "command": "evaluate", "files": [{"path": "thesis.tex",
          "size": 13, "sha256": ")" +
          sha256_hex("something else") + "\"}]}");
  const auto before = snapshot(".");
  std::string e = input_error([&] { OutputDirectory out("thesis", "evaluate"); });
  EXPECT_NE(e.find("thesis: its .plumekit-output.json is an older plumekit's, which lists "
                   "thesis.tex without its SHA-256"),
            std::string::npos)
      << e;
  e = input_error([&] { OutputDirectory out("copied", "evaluate"); });
  EXPECT_NE(e.find("copied: thesis.tex is not the file plumekit wrote there"), std::string::npos)
      << e;
  EXPECT_EQ(snapshot("."), before);
  // An older marker alone in its folder lists nothing to delete.
  put("old/.plumekit-output.json", R"({"format": "plumekit-output/1", "command": "evaluate"})");
  write_run("old", "evaluate", "new");
  EXPECT_EQ(slurp("old/result.txt"), "new");
}

// evaluate --method a,b: one output holding one per method, each of which may be rewritten alone.
TEST_F(OutputTargetTest, NestedOutputsAreCheckedByTheirOwnMarkers) {
  {
    OutputDirectory whole("all", "evaluate");
    for (const char* name : {"ste", "zigzag"}) {
      OutputDirectory one(whole.open() / name, "evaluate");
      put(one.open() / "runs.csv", name);
      one.commit();
    }
    whole.commit();
  }
  EXPECT_EQ(slurp("all/zigzag/runs.csv"), "zigzag");
  EXPECT_TRUE(fs::exists("all/zigzag/.plumekit-output.json"));
  write_run("all/zigzag", "evaluate", "alone");  // rewritten alone: still ours
  EXPECT_NO_THROW(OutputDirectory again("all", "evaluate"));
  put("all/ste/runs.csv", "edited");
  const std::string e = input_error([&] { OutputDirectory again("all", "evaluate"); });
  EXPECT_NE(e.find("runs.csv is not the file plumekit wrote there"), std::string::npos) << e;
  EXPECT_NE(e.find("all/ste"), std::string::npos) << e;
  EXPECT_EQ(slurp("all/ste/runs.csv"), "edited");
}

// Issue 44: one run at a time writes an output; the lock file goes when done.
TEST_F(OutputTargetTest, SecondWriterOfAnOutputIsRefusedAtOnce) {
  {
    OutputDirectory first("runs/run", "evaluate");
    put(first.open() / "result.txt", "first");
    EXPECT_TRUE(fs::exists("runs/run.plumekit-lock"));
    const std::string e = input_error([&] { OutputDirectory second("runs/run", "evaluate"); });
    EXPECT_NE(e.find("runs/run: another plumekit run is writing it"), std::string::npos) << e;
    EXPECT_NE(input_error([&] { write_output_file("runs/run", "x"); }).find("another plumekit run"),
              std::string::npos);
    first.commit();
    EXPECT_FALSE(fs::exists("runs/run.plumekit-lock"));
  }
  EXPECT_EQ(slurp("runs/run/result.txt"), "first");
  write_run("runs/run", "evaluate", "second");  // free again
  EXPECT_EQ(std::distance(fs::directory_iterator("runs"), fs::directory_iterator{}), 1);
  // A refused or uncommitted run leaves no lock behind either.
  { OutputDirectory never("runs/other", "evaluate"); }
  EXPECT_EQ(std::distance(fs::directory_iterator("runs"), fs::directory_iterator{}), 1);
  // A user's file of the lock's name is refused, never removed.
  put("runs/run.plumekit-lock", "my notes");
  const std::string e = input_error([&] { write_run("runs/run", "evaluate", "third"); });
  EXPECT_NE(e.find("runs/run.plumekit-lock: exists beside the output"), std::string::npos) << e;
  EXPECT_EQ(slurp("runs/run.plumekit-lock"), "my notes");
  EXPECT_EQ(slurp("runs/run/result.txt"), "second");
}

// CI once found a lock left behind by a Ctrl-C that came while the lock file
// was being made, before it was held: a lock is registered before it exists.
TEST_F(OutputTargetTest, AnInterruptWhileALockIsMadeRemovesItButNotAUsersFile) {
  auto interrupted_child = [](const fs::path& lock_file, bool make_it) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      install_interrupt_cleanup();
      register_lock(lock_file, -1);
      if (make_it) put(lock_file, kLockFileText);
      ::raise(SIGINT);
      ::pause();
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  EXPECT_EQ(interrupted_child(dir / "out.plumekit-lock", true), 130);
  EXPECT_FALSE(fs::exists(dir / "out.plumekit-lock"));
  put(dir / "mine.plumekit-lock", "my notes");
  EXPECT_EQ(interrupted_child(dir / "mine.plumekit-lock", false), 130);
  EXPECT_EQ(slurp(dir / "mine.plumekit-lock"), "my notes");
}

TEST_F(OutputTargetTest, PartsShareAnInPlaceFolderButNotWithAWholeWriter) {
  auto own = [](const std::string& n) { return n == "shards"; };
  OutputClaim a = claim_output_directory("ds", "dataset", {"dataset"}, own, "parameters.json");
  OutputClaim b = claim_output_directory("ds", "dataset", {"dataset"}, own, "parameters.json");
  EXPECT_FALSE(a.existed);
  EXPECT_NE(input_error([&] { OutputDirectory out("ds", "dataset"); }).find("another plumekit run"),
            std::string::npos);
  a.lock.release();
  EXPECT_TRUE(fs::exists("ds.plumekit-lock"));  // b holds it still
  b.lock.release();
  EXPECT_FALSE(fs::exists("ds.plumekit-lock"));
}

TEST_F(OutputTargetTest, InPlaceClaimAcceptsOwnLayoutOnly) {
  auto own = [](const std::string& n) { return n == "shards" || n == "parameters.json"; };
  EXPECT_FALSE(
      claim_output_directory("ds", "dataset generate", {"dataset generate"}, own, "parameters.json")
          .existed);
  EXPECT_TRUE(fs::exists("ds/.plumekit-output.json"));
  put("ds/parameters.json", "{}");
  EXPECT_TRUE(
      claim_output_directory("ds", "dataset generate", {"dataset generate"}, own, "parameters.json")
          .existed);
  put("ds/thesis.pdf", "x");
  EXPECT_NE(input_error([&] {
              claim_output_directory("ds", "dataset generate", {"dataset generate"}, own,
                                     "parameters.json");
            }).find("thesis.pdf"),
            std::string::npos);
  // a dataset from before markers: recognised by its parameters.json
  put("legacy/parameters.json", "{}");
  EXPECT_TRUE(claim_output_directory("legacy", "dataset generate", {"dataset generate"}, own,
                                     "parameters.json")
                  .existed);
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
