// Safe by default, end to end: the output rule on every writing command, the
// exit-code contract, JSON errors, and interrupted runs that leave nothing.
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"
#include "support/files.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using Result = plumekit::test::CliResult;
using plumekit::test::slurp;

const fs::path kData = PLUMEKIT_DATA_DIR;

const auto& put = plumekit::test::put_file;
using plumekit::test::snapshot;

class Safety : public plumekit::test::CliTest {
 protected:
  // Runs in the test's folder, so that relative paths and "." mean it.
  Result here(const std::string& args) {
    const fs::path before = fs::current_path();
    fs::current_path(dir);
    const Result r = run(args);
    fs::current_path(before);
    return r;
  }
  // A folder that must come through a refused command byte for byte.
  fs::path thesis() {
    put(dir / "work" / "thesis.tex", "years of work");
    put(dir / "work" / "data" / "run.csv", "1,2,3\n");
    return dir / "work";
  }
  // One small map for the STE commands: the empty test map, one source.
  fs::path one_map_dir() {
    fs::create_directories(dir / "maps");
    fs::copy_file(kData / "test-maps" / "test-0-empty.json", dir / "maps" / "test-0-empty.json");
    return dir / "maps";
  }
  static std::string quick_ste() {
    return " --plume-model gaussian --runs 1 --sources 1 --max-samples 2 --threads 1";
  }
  // Starts `plumekit ARGS...` in the background with its output discarded and
  // SIGINT at its default, as from a terminal, even if this test runs in the background.
  static pid_t start(std::vector<std::string> args) {
    const std::string exe = PLUMEKIT_EXE;
    args.insert(args.begin(), exe);
    std::vector<char*> argv;
    for (std::string& a : args)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, exe.c_str(), &actions, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    return rc == 0 ? pid : -1;
  }
  // Waits until an entry whose name holds `part` appears under `folder`: up to 2 minutes, as a
  // loaded CI machine can take a while to start a run.
  static bool appears(const fs::path& folder, const std::string& part) {
    for (int i = 0; i < 2400; ++i) {
      std::error_code ec;
      for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string().find(part) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }
  // Sends `sig` to `pid` and returns its exit status (-1 if it did not exit).
  static int stop(pid_t pid, int sig) {
    int status = 0;
    if (::kill(pid, sig) != 0 || ::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status);
  }
  // Starts a slow evaluation (the physics plume, still running when the test acts) into `out`
  // and waits until it writes its temporary output. Its pid, or -1 with the failure recorded
  // (and the run killed) when it did not start or never wrote.
  pid_t start_slow_evaluate(const fs::path& maps, const fs::path& out,
                            const std::string& method = "ste") {
    const pid_t pid =
        start({"evaluate", "--map-dir", maps.string(), "--out", out.string(), "--plume-model",
               "physics", "--runs", "3", "--threads", "1", "--method", method});
    if (pid <= 0) {
      ADD_FAILURE() << "plumekit did not start";
      return -1;
    }
    if (!appears(dir, ".plumekit-tmp-")) {
      ADD_FAILURE() << "the run never started writing";
      stop(pid, SIGKILL);
      return -1;
    }
    return pid;
  }
};

TEST_F(Safety, EvaluateRefusesAFolderWithFilesItDidNotWrite) {
  const fs::path work = thesis();
  const auto before = snapshot(work);
  const Result r =
      run("evaluate --map-dir " + one_map_dir().string() + " --out " + work.string() + quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("holds files plumekit did not write"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("thesis.tex"), std::string::npos) << r.err;
  EXPECT_EQ(snapshot(work), before);
}

TEST_F(Safety, EvaluateRefusesTheCurrentFolderTheInputsAndAFile) {
  const fs::path maps = one_map_dir();
  put(dir / "keep.txt", "keep");
  const auto before = snapshot(dir);
  Result r = here("evaluate --map-dir maps --out ." + quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("the current folder"), std::string::npos) << r.err;
  r = run("evaluate --map-dir " + maps.string() + " --out " + maps.string() + quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("is also an input"), std::string::npos) << r.err;
  r = run("evaluate --map-dir " + maps.string() + " --out " + (dir / "keep.txt").string() +
          quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("is a file, but this output is a folder"), std::string::npos) << r.err;
  EXPECT_EQ(snapshot(dir), before);
}

TEST_F(Safety, EvaluateNamesPicturesAfterFilesNotMapNamesAndReplacesItsOwnOutput) {
  fs::create_directories(dir / "maps");
  std::string text = slurp(kData / "test-maps" / "test-0-empty.json");
  const std::string name = "\"name\": \"";
  const std::size_t at = text.find(name);
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = text.find('"', at + name.size());
  text.replace(at + name.size(), end - at - name.size(), "../../escaped");
  put(dir / "maps" / "a.json", text);
  put(dir / "maps" / "b.json", text);  // the same name twice
  const fs::path out = dir / "runs" / "eval";
  Result r =
      run("evaluate --map-dir " + (dir / "maps").string() + " --out " + out.string() + quick_ste());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "trajectories" / "a.png"));
  EXPECT_TRUE(fs::exists(out / "trajectories" / "b.png"));
  EXPECT_FALSE(fs::exists(dir / "escaped.png"));
  EXPECT_FALSE(fs::exists(dir / "runs" / "escaped.png"));
  // A second run replaces its own earlier output.
  r = run("evaluate --map-dir " + (dir / "maps").string() + " --out " + out.string() + quick_ste());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "runs"), fs::directory_iterator{}), 1);
}

TEST_F(Safety, InterruptedEvaluateLeavesNoTemporary) {
  const fs::path maps = one_map_dir();
  const fs::path out = dir / "eval";
  // Once the temporary output folder is there, press Ctrl-C.
  const pid_t pid = start_slow_evaluate(maps, out);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(stop(pid, SIGINT), 130);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find("plumekit-"), std::string::npos) << e.path();
  EXPECT_FALSE(fs::exists(out));
}

// Issue 44: the folder made for the methods' folders, and the parents made for
// it, go too: nothing is left that was not there before.
TEST_F(Safety, StoppedEvaluateOfSeveralMethodsLeavesNothing) {
  const fs::path maps = one_map_dir();
  const auto before = snapshot(dir);
  const pid_t pid = start_slow_evaluate(maps, dir / "new" / "eval", "all");
  ASSERT_GT(pid, 0);
  EXPECT_EQ(stop(pid, SIGTERM), 143);
  EXPECT_EQ(snapshot(dir), before);
}

// Issue 44: two runs into one --out: the second fails at once, the first is untouched.
TEST_F(Safety, ASecondRunIntoTheSameOutputIsRefusedAtOnce) {
  const fs::path maps = one_map_dir();
  const fs::path out = dir / "eval";
  const pid_t pid = start_slow_evaluate(maps, out);
  ASSERT_GT(pid, 0);
  const Result r =
      run("evaluate --map-dir " + maps.string() + " --out " + out.string() + quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(out.string() + ": another plumekit run is writing it"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(dir / "eval.plumekit-lock"));  // the first run's, still held
  EXPECT_EQ(stop(pid, SIGTERM), 143);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "eval.plumekit-lock"));
}

// Issue 44: the folder of several methods is an output like any other: checked
// before any work, and replaced whole, so that no earlier method's results stay.
TEST_F(Safety, EvaluateOfSeveralMethodsChecksAndReplacesTheWholeFolder) {
  const fs::path maps = one_map_dir();
  const fs::path work = thesis();
  const auto before = snapshot(work);
  Result r = run("evaluate --map-dir " + maps.string() + " --out " + work.string() +
                 " --method zigzag,sweeping --max-steps 30" + quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(work.string() + ": holds files plumekit did not write"), std::string::npos)
      << r.err;
  EXPECT_EQ(snapshot(work), before);
  const fs::path out = dir / "eval";
  r = run("evaluate --map-dir " + maps.string() + " --out " + out.string() +
          " --method zigzag,sweeping --max-steps 30" + quick_ste());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "zigzag" / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "sweeping" / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "zigzag" / ".plumekit-output.json"));  // each its own output too
  r = run("evaluate --map-dir " + maps.string() + " --out " + out.string() +
          " --method zigzag,surge-cast --max-steps 30" + quick_ste());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "surge-cast" / "summary.json"));
  EXPECT_FALSE(fs::exists(out / "sweeping"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}),
            3);  // + maps, work
}

// Issue 44: a marker that lists a user's file (copied, or of an older plumekit
// without checksums) does not make it plumekit's to delete.
TEST_F(Safety, AForgedMarkerDoesNotGetFilesDeleted) {
  const fs::path maps = one_map_dir();
  const fs::path work = thesis();
  put(work / ".plumekit-output.json", R"({"format": "plumekit-output/1", "command": "evaluate",)"
                                      R"( "files": ["thesis.tex", "data/run.csv"]})");
  const auto before = snapshot(work);
  Result r = run("evaluate --map-dir " + maps.string() + " --out " + work.string() + quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(work.string() + ": its .plumekit-output.json is an older plumekit's"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("data/run.csv"), std::string::npos) << r.err;
  // A marker of plumekit's own output copied beside the user's files.
  const fs::path ev = dir / "ev";
  ASSERT_EQ(run("evaluate --map-dir " + maps.string() + " --out " + ev.string() + quick_ste()).code,
            0);
  put(ev / "runs.csv", "my edited results\n");
  const auto edited = snapshot(ev);
  r = run("evaluate --map-dir " + maps.string() + " --out " + ev.string() + quick_ste());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(ev.string() + ": runs.csv is not the file plumekit wrote there"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(snapshot(ev), edited);
  EXPECT_EQ(snapshot(work), before);
}

TEST_F(Safety, AStaleTemporaryOfAKilledRunIsRemovedByTheNextRun) {
  // As a run killed outright leaves it: marked, its process (above pid_max) gone.
  const fs::path stale = dir / "wind.plumekit-tmp-999999999-0";
  put(stale / "wind" / "u.npy", "half");
  put(stale / ".plumekit-temporary", "plumekit-temporary/1\nwind.plumekit-tmp-999999999-0\n");
  // Issue 44: a user's folder of that look, without the marker, stays.
  const fs::path mine = dir / "wind.plumekit-tmp-999999999-1";
  put(mine / "thesis.tex", "years of work");
  const Result r = run("flow " + (kData / "maps" / "empty.json").string() + " --cell 0.2 --out " +
                       (dir / "wind").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_EQ(slurp(mine / "thesis.tex"), "years of work");
  EXPECT_TRUE(fs::exists(dir / "wind" / "u.npy"));
}

// Issue 44: a resumed dataset removes its own stale temporaries, never a look-alike.
TEST_F(Safety, AResumedDatasetRemovesOnlyMarkedTemporaries) {
  const fs::path ds = dir / "ds";
  const std::string args =
      "dataset generate --maps 1 --sources 1 --simulator "
      "advection-diffusion --out " +
      ds.string();
  ASSERT_EQ(run(args).code, 0);
  const fs::path stale = ds / "shards" / "shard-00000.plumekit-tmp-999999999-0";
  put(stale / "shard-00000" / "inputs.npy", "half");
  put(stale / ".plumekit-temporary",
      "plumekit-temporary/1\nshard-00000.plumekit-tmp-999999999-0\n");
  put(ds / "shards" / "shard-00000.plumekit-tmp-999999999-1" / "notes.txt", "mine");
  put(ds / "wind" / "map-00000.tmp-999999999-0" / "notes.txt", "mine too");  // an older form
  const Result r = run(args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_EQ(slurp(ds / "shards" / "shard-00000.plumekit-tmp-999999999-1" / "notes.txt"), "mine");
  EXPECT_EQ(slurp(ds / "wind" / "map-00000.tmp-999999999-0" / "notes.txt"), "mine too");
}

TEST_F(Safety, EveryWritingCommandRefusesAFolderItDidNotWrite) {
  const fs::path work = thesis();
  const auto before = snapshot(work);
  const std::string map = (kData / "maps" / "cluttered-1.json").string();
  const std::string w = work.string();
  for (const std::string& cmd : {
           "flow " + map + " --cell 0.2 --out " + w,
           "plume " + map + " --source 1,2 --out " + w,
           "predict " + map + " --source 1,2 --out " + w,
           "localize " + map + " --source 1,2 --plume-model gaussian --out " + w,
           "demo --plume-model gaussian --out " + w,
           "maps random --count 1 --out " + w,
           "dataset generate --maps 1 --sources 1 --out " + w,
       }) {
    const Result r = run(cmd);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find("did not write"), std::string::npos) << cmd << "\n" << r.err;
    EXPECT_EQ(snapshot(work), before) << cmd;
  }
  // dataset merge, given a real part to merge
  const fs::path part = dir / "part";
  for (const char* k : {"0/2", "1/2"})
    ASSERT_EQ(
        run(std::string("dataset generate --maps 2 --sources 1 --simulator advection-diffusion "
                        "--shard ") +
            k + " --out " + part.string())
            .code,
        0);
  const Result r = run("dataset merge " + part.string() + " --out " + w);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("did not write"), std::string::npos) << r.err;
  EXPECT_EQ(snapshot(work), before);
}

TEST_F(Safety, PicturesAndMapsOverwriteOnlyWhatPlumekitWrote) {
  const std::string map = (kData / "maps" / "cluttered-1.json").string();
  put(dir / "photo.png", "my holiday");
  put(dir / "hand.json", "{\"my\": \"map\"}");
  for (const std::string& cmd :
       {"map render " + map + " --out " + (dir / "photo.png").string(),
        "plan " + map + " --from 1,1 --to 9,3 --out " + (dir / "photo.png").string(),
        "map import-ros " + (kData / "ros" / "office.yaml").string() + " --out " +
            (dir / "hand.json").string()}) {
    const Result r = run(cmd);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find("was not written by plumekit"), std::string::npos) << r.err;
  }
  EXPECT_EQ(slurp(dir / "photo.png"), "my holiday");
  EXPECT_EQ(slurp(dir / "hand.json"), "{\"my\": \"map\"}");
  // plumekit's own pictures and imported maps are rewritten.
  const fs::path png = dir / "map.png", json = dir / "office.json";
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(run("map render " + map + " --out " + png.string()).code, 0);
    EXPECT_EQ(run("map import-ros " + (kData / "ros" / "office.yaml").string() + " --out " +
                  json.string())
                  .code,
              0);
  }
  EXPECT_EQ(run("map validate " + json.string()).code, 0);
  // A folder named as a picture.
  fs::create_directory(dir / "folder.png");
  const Result r = run("map render " + map + " --out " + (dir / "folder.png").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;
}

TEST_F(Safety, UserMistakesExitTwoNamingThePath) {
  const std::string map = (kData / "maps" / "cluttered-1.json").string();
  put(dir / "file", "x");
  const std::string under_file = (dir / "file" / "out").string();
  Result r;
  for (const std::string& cmd : {
           "plume " + map + " --source 1,2 --out " + under_file,
           "localize " + map + " --source 1,2 --plume-model gaussian --out " + under_file,
           "maps random --count 1 --out " + under_file,
           "dataset generate --maps 1 --sources 1 --out " + under_file,
           "demo --plume-model gaussian --out " + under_file,
       }) {
    const Result r = run(cmd);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find((dir / "file").string()), std::string::npos) << cmd << "\n" << r.err;
  }
  // A place nobody may write: the kernel's /proc.
  r = run("maps random --count 1 --out /proc/plumekit-test");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("/proc/plumekit-test"), std::string::npos) << r.err;
  fs::create_directory(dir / "folder");
  r = run("map import-ros " + (dir / "folder").string() + " --out " + (dir / "x.json").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;
  r = run("map validate " + dir.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is a folder"), std::string::npos) << r.err;
}

TEST_F(Safety, JsonReportsParseErrorsAndUnknownCommands) {
  Result r = run("flow --json --cell abc --out x");
  EXPECT_EQ(r.code, 2);
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], false);
  EXPECT_EQ(j["exit_code"], 2);
  EXPECT_NE(j["error"].get<std::string>().find("--cell"), std::string::npos) << j.dump();
  r = run("frobnicate --json");
  EXPECT_EQ(r.code, 2);
  j = nlohmann::json::parse(r.out);
  EXPECT_NE(j["error"].get<std::string>().find("'frobnicate' is not a command"), std::string::npos)
      << j.dump();
  r = run("map frobnicate");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'frobnicate' is not a command of plumekit map"), std::string::npos)
      << r.err;
}

TEST_F(Safety, LibraryRangeErrorsNameTheFlagAndWriteNothing) {
  const std::string map = (kData / "maps" / "cluttered-1.json").string();
  const fs::path out = dir / "never";
  const struct {
    std::string args, flag;
  } cases[] = {
      {"flow " + map + " --cell -1 --out " + out.string(), "--cell"},  // 0 is the default
      {"flow " + map + " --nu 1e9 --out " + out.string(), "--nu"},
      {"dataset generate --maps 1 --sources 1 --cell nan --out " + out.string(), "--cell"},
      {"dataset generate --maps 1 --sources 1 --families l-shape,U --out " + out.string(),
       "--families"},
      {"dataset generate --maps 1 --sources 1 --filaments-per-second 0 --out " + out.string(),
       "--filaments-per-second"},
      {"plume " + map + " --source 1,2 --release-rate nan --out " + out.string(), "--release-rate"},
      {"plume " + map + " --source 1,2 --release-rate -5 --out " + out.string(), "--release-rate"},
      {"localize " + map + " --source 1,2 --plume-model gaussian --noise nan --out " + out.string(),
       "--noise"},
      {"map render " + map + " --px-per-m nan --out " + (dir / "never.png").string(), "--px-per-m"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.args + " --json");
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["error"].get<std::string>().rfind(c.flag + ": ", 0), 0u) << c.args << "\n" << r.out;
    for (const auto& e : fs::directory_iterator(dir))
      ADD_FAILURE() << c.args << " left " << e.path();
  }
}

TEST_F(Safety, WrittenFilesRecordNoAbsolutePath) {
  const fs::path maps = one_map_dir();
  const fs::path map = maps / "test-0-empty.json";
  Result r =
      run("localize " + map.string() + " --source 5,2 --plume-model gaussian --max-samples 2 " +
          "--out " + (dir / "loc").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(dir / "loc" / "run.json").find(dir.string()), std::string::npos);
  r = run("evaluate --map-dir " + maps.string() + " --out " + (dir / "ev").string() + quick_ste());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(dir / "ev" / "summary.json").find(dir.string()), std::string::npos);
}

}  // namespace
