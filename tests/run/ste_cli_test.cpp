// plumekit localize / evaluate / demo from the command line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"
#include "support/small_map.hpp"

namespace plumekit::test {
namespace {

using nlohmann::json;

// The data a report.html carries (run/evaluation_html.hpp): the JSON of its data script, which
// holds no "</" (that would end the script early).
json report_page_data(const std::filesystem::path& page) {
  const std::string html = slurp(page);
  const std::string open = "<script type=\"application/json\" id=\"plumekit-data\">";
  const std::size_t at = html.find(open), end = html.find("</script>", at);
  EXPECT_NE(at, std::string::npos) << page;
  if (at == std::string::npos) return json();
  const std::string data = html.substr(at + open.size(), end - at - open.size());
  EXPECT_EQ(data.find("</"), std::string::npos);
  return json::parse(data);
}

class SteCli : public CliTest {
 protected:
  std::string write_map() { return write_small_map(dir); }
};

TEST_F(SteCli, LocalizeJsonAndPictures) {
  const std::string map = write_map();
  const CliResult r = run("localize " + map +
                          " --source 4.5,0.5 --start 1,2.5 --plume-model physics --seed 3 --out " +
                          (dir / "run").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  for (const char* key :
       {"estimate", "error_m", "samples", "distance_m", "compute_s", "stopped_by"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_LT(j["error_m"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["source_cell"].get<double>(), 0.1);  // the physics model's default
  EXPECT_TRUE(std::filesystem::exists(dir / "run" / "trajectory.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "run" / "posterior.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "run" / "run.json"));
}

// Issue 20: every method through the same commands, outputs and pictures.
TEST_F(SteCli, LocalizeAndEvaluateRunAnyMethod) {
  const std::string map = write_map();
  CliResult r = run("localize " + map + " --source 4.5,0.5 --start 1,2.5 --method surge-cast " +
                    "--seed 3 --out " + (dir / "track").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  json j = json::parse(r.out);
  EXPECT_EQ(j["method"], "surge-cast");
  EXPECT_TRUE(j.contains("reached_source_box"));
  EXPECT_TRUE(std::filesystem::exists(dir / "track" / "trajectory.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "track" / "posterior.png"));  // a tracker has none
  EXPECT_FALSE(j["out"].contains("posterior"));
  r = run("localize " + map + " --source 4.5,0.5 --start 1,2.5 --method pf-sweep --seed 3 --out " +
          (dir / "pf").string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "pf" / "posterior.png"));  // its particles
  r = run("evaluate --map-dir " + (dir / "maps").string() +
          " --runs 1 --method zigzag --max-steps 30 --json --out " + (dir / "ev").string());
  ASSERT_EQ(r.code, 0) << r.err;
  j = json::parse(r.out);
  EXPECT_EQ(j["method"], "zigzag");
  EXPECT_TRUE(j["overall"].contains("reached_source_box"));
  EXPECT_EQ(j["method_options"]["zigzag_alpha_deg"].get<double>(), 60.0);
  const std::string csv = slurp(dir / "ev" / "runs.csv");
  EXPECT_EQ(csv.rfind("map,source_index,run,source_x,source_y,start_x,start_y,estimate_x,"
                      "estimate_y,error_m,samples,distance_m,mission_s,stopped_by,"
                      "first_detection_s,within_1m_s,within_0_5m_s,optimum_s,over_optimum,"
                      "gsl_bench,reached,distance_overhead\n",
                      0),
            0u)
      << csv;
  r = run("localize " + map + " --source 4.5,0.5 --method infotaxis");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--method: unknown method 'infotaxis'"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.5,0.5 --method zigzag --zigzag-angle 95");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--zigzag-angle"), std::string::npos) << r.err;
}

// Issue 44: the time summary's parts (wind, model build, plume simulation, decisions, other) add
// up to its total, in the JSON and as printed; several methods print their own parts and one total.
TEST_F(SteCli, TheTimeSummaryAddsUpAndSeveralMethodsGetOneTotal) {
  const std::string map = write_map();
  const std::string common = " --source 4.5,0.5 --start 1,2.5 --plume-model gaussian --seed 3";
  CliResult r = run("localize " + map + common + " --json --out " + (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json t = json::parse(r.out)["time"];
  double parts = 0;
  for (const char* key : {"wind_s", "model_build_s", "plume_simulation_s", "decisions_s"}) {
    ASSERT_TRUE(t.contains(key)) << t;
    EXPECT_GE(t[key].get<double>(), 0.0) << key;
    parts += t[key].get<double>();
  }
  EXPECT_GE(t["other_s"].get<double>(), 0.0);
  EXPECT_NEAR(parts + t["other_s"].get<double>(), t["total_s"].get<double>(), 1e-9) << t;
  EXPECT_EQ(json::parse(slurp(dir / "run" / "run.json"))["time"].size(), 6u);

  // As printed: "time T s (wall clock): wind a s + model build b s + ... + other e s", in tenths.
  r = run("localize " + map + common);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::size_t at = r.out.find("time ");
  ASSERT_NE(at, std::string::npos) << r.out;
  std::istringstream line(r.out.substr(at, r.out.find(';', at) - at));
  std::string word, label;
  double total = -1, sum = 0;
  std::vector<std::string> labels;
  while (line >> word) {
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end != word.c_str() && *end == '\0') {
      if (total < 0)
        total = v;
      else
        sum += v, labels.push_back(label);
      label.clear();
    } else if (word != "s" && word != "+" && word != "(wall" && word != "clock):" &&
               word != "time") {
      label += (label.empty() ? "" : " ") + word;
    }
  }
  EXPECT_EQ(labels, (std::vector<std::string>{"wind", "model build", "plume simulation",
                                              "decisions", "other"}))
      << r.out;
  EXPECT_NEAR(sum, total, 1e-9) << r.out;

  // Several methods: each one's own model build and decisions, and one total after them.
  r = run("evaluate --map-dir " + (dir / "maps").string() +
          " --plume-model gaussian --max-samples 6 --max-steps 15 --runs 1 --method ste,zigzag "
          "--out " +
          (dir / "ev").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find(") in "), std::string::npos) << "no method claims the total:\n" << r.out;
  EXPECT_NE(r.out.find("STE (gaussian)): model build "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("zigzag): model build "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n\nall 2 methods in "), std::string::npos) << r.out;
}

// Several methods in one world (world/shared_plume.hpp): OUT/NAME/ is byte for byte what
// `--method NAME --out OUT/NAME` writes, the pictures included.
TEST_F(SteCli, SeveralMethodsInOneWorldWriteWhatEachWritesAlone) {
  write_map();
  const std::string maps = (dir / "maps").string();
  const std::string common = " --plume-model gaussian --max-samples 6 --max-steps 15 --runs 2";
  CliResult r = run("evaluate --map-dir " + maps + common +
                    " --method ste,zigzag,pf-sweep --json --out " + (dir / "all").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["methods"].size(), 3u);
  EXPECT_EQ(j["methods"][1]["method"], "zigzag");
  EXPECT_TRUE(j["methods"][1]["result"]["overall"].contains("reached_source_box"));
  // One table of all of them (issue 48), each row its method's own summary and time.
  ASSERT_EQ(j["comparison"].size(), 3u);
  const std::string table = slurp(dir / "all" / "comparison.md");
  const std::string csv = slurp(dir / "all" / "comparison.csv");
  for (std::size_t m = 0; m < 3; ++m) {
    const json& row = j["comparison"][m];
    const json& own = j["methods"][m];
    EXPECT_EQ(row["success_0_5m"], own["result"]["overall"]["success_0_5m"]) << m;
    EXPECT_EQ(row["median_mission_s"], own["result"]["overall"]["median_mission_s"]) << m;
    EXPECT_DOUBLE_EQ(row["decisions_s"].get<double>(), own["decisions_s"].get<double>()) << m;
    const std::string name = row["method"], runs = std::to_string(row["runs"].get<int>());
    EXPECT_EQ(runs, "4");  // 2 runs of each of the map's 2 sources
    EXPECT_NE(table.find("| " + name + " | " + runs + " | "), std::string::npos) << table;
    EXPECT_NE(csv.find("\n" + name + "," + runs + ","), std::string::npos) << csv;
  }
  EXPECT_EQ(j["comparison"][0]["method"], "STE (gaussian)");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  // report.html (issue 48): every method's runs, each with its track, in one page's data.
  const json page = report_page_data(dir / "all" / "report.html");
  EXPECT_EQ(page["format"], "plumekit-report/1");
  ASSERT_EQ(page["methods"].size(), 3u);
  EXPECT_EQ(page["methods"][1]["label"], "zigzag");
  EXPECT_EQ(page["methods"][1]["summary"]["overall"], j["methods"][1]["result"]["overall"]);
  ASSERT_EQ(page["runs"]["rows"].size(), 12u);
  ASSERT_EQ(page["tracks"].size(), 12u);
  const json tracks = json::parse(slurp(dir / "all" / "zigzag" / "tracks.json"));
  for (std::size_t k = 0; k < 4; ++k) {
    const json& row = page["runs"]["rows"][4 + k];
    EXPECT_EQ(row[0], 1);  // zigzag's
    EXPECT_EQ(page["tracks"][4 + k], tracks["runs"][k]);
    // The row's start is its track's first point, its source the map's.
    EXPECT_EQ(row[12], tracks["runs"][k]["robots"][0]["path"][0]);
    EXPECT_EQ(row[10], tracks["runs"][k]["source"][0]);
    // A tracker's path: from its start through each stop.
    EXPECT_GE(tracks["runs"][k]["robots"][0]["path"].size(),
              tracks["runs"][k]["robots"][0]["stops"].size() / 2);
  }
  EXPECT_EQ(page["maps"][0]["name"], "small");
  for (const std::string m : {"ste", "zigzag", "pf-sweep"}) {
    r = run("evaluate --map-dir " + maps + common + " --method " + m + " --out " +
            (dir / ("one-" + m)).string());
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* f : {"runs.csv", "summary.json", "boxplot-error.png", "boxplot-samples.png",
                          "trajectories/small.png", "tracks.json", "report.html"}) {
      const std::string bytes = slurp(dir / "all" / m / f);
      EXPECT_FALSE(bytes.empty()) << m << ": " << f;
      EXPECT_EQ(bytes, slurp(dir / ("one-" + m) / f)) << m << ": " << f;
    }
  }
  // Parts of several methods: OUT/NAME/ part folders, which merge method by method.
  for (int k = 0; k < 2; ++k) {
    r = run("evaluate --map-dir " + maps + common + " --method ste,zigzag --shard " +
            std::to_string(k) + "/2 --out " + (dir / ("part-" + std::to_string(k))).string());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  for (const std::string m : {"ste", "zigzag"}) {
    r = run("evaluate merge " + (dir / "part-0" / m).string() + " " +
            (dir / "part-1" / m).string() + " --out " + (dir / ("merged-" + m)).string());
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* f : {"runs.csv", "summary.json"})
      EXPECT_EQ(slurp(dir / ("merged-" + m) / f), slurp(dir / ("one-" + m) / f)) << m << ": " << f;
  }
  // The plume model's settings are STE's alone.
  EXPECT_FALSE(json::parse(slurp(dir / "all" / "zigzag" / "summary.json")).contains("sigma_m"));
  EXPECT_TRUE(json::parse(slurp(dir / "all" / "ste" / "summary.json")).contains("sigma_m"));
  r = run("evaluate --map-dir " + maps + " --method zigzag,ste,zigzag --out " +
          (dir / "twice").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("zigzag is named twice"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "twice"));
  r = run("localize " + (dir / "maps" / "small.json").string() + " --source 4.5,0.5 --method all");
  EXPECT_EQ(r.code, 2);  // one robot, one method
  EXPECT_NE(r.err.find("unknown method 'all'"), std::string::npos) << r.err;
}

// Seed 004 ch. 15's benchmark protocol: a run of any method ends on arriving near the source;
// the world's release rate can differ from the models' nominal (issue 21).
TEST_F(SteCli, SuccessRadiusEndsAnyRunOnArrivalAndTheReleaseRateIsTheWorlds) {
  const std::string map = write_map();
  CliResult r = run("localize " + map +
                    " --source 4.5,0.5 --start 1,2.5 --plume-model gaussian --success-radius 5 "
                    "--release-rate 500 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  json j = json::parse(r.out);
  EXPECT_EQ(j["stopped_by"], "reached");  // it starts 4 m from the source
  EXPECT_EQ(j["samples"], 1);
  r = run("evaluate --map-dir " + (dir / "maps").string() +
          " --method levy-taxis --runs 1 --max-steps 5 --success-radius 0.3 --release-rate 500 "
          "--json --out " +
          (dir / "ev").string());
  ASSERT_EQ(r.code, 0) << r.err;
  j = json::parse(r.out);
  EXPECT_EQ(j["success_radius"].get<double>(), 0.3);
  EXPECT_EQ(j["release_rate"].get<double>(), 500.0);
  EXPECT_EQ(j["method_options"]["gradient_threshold"].get<double>(), 50.0);
  r = run("localize " + map + " --source 4.5,0.5 --release-rate 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--release-rate"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.5,0.5 --success-radius -1");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--success-radius"), std::string::npos) << r.err;
}

// Issue 21: robot teams (seed 004 ch. 13) through localize and evaluate.
TEST_F(SteCli, TeamsRunThroughLocalizeAndEvaluate) {
  const std::string map = write_map();
  const std::string team = "localize " + map +
                           " --source 4.5,0.5 --start 1,2.5 --plume-model physics --seed 3 "
                           "--robots 2 --team cooperative --max-samples 10 --json --out ";
  CliResult r = run(team + (dir / "team").string());
  ASSERT_EQ(r.code, 0) << r.err;
  json j = json::parse(r.out);
  ASSERT_TRUE(j.contains("team"));
  EXPECT_EQ(j["team"]["robots"], 2);
  EXPECT_EQ(j["team"]["strategy"], "cooperative");
  ASSERT_EQ(j["team"]["members"].size(), 2u);
  int samples = 0;
  for (const json& m : j["team"]["members"]) {
    samples += m["samples"].get<int>();
    EXPECT_EQ(m["steps"].size(), m["samples"].get<std::size_t>());
  }
  EXPECT_EQ(j["samples"].get<int>(), samples);  // summed over the team
  EXPECT_TRUE(std::filesystem::exists(dir / "team" / "trajectory.png"));
  // The same seed gives the same run: every field but the measured times.
  ASSERT_EQ(run(team + (dir / "again").string()).code, 0);
  const auto untimed = [](json v) {
    std::function<void(json&)> strip = [&strip](json& x) {
      if (x.is_object())
        for (const char* key : {"compute_s", "median_step_s", "wind_s", "table_build_s", "time"})
          x.erase(key);
      if (x.is_structured())
        for (json& e : x)
          strip(e);
    };
    strip(v);
    return v;
  };
  EXPECT_EQ(untimed(json::parse(slurp(dir / "team" / "run.json"))),
            untimed(json::parse(slurp(dir / "again" / "run.json"))));
  r = run("evaluate --map-dir " + (dir / "maps").string() +
          " --runs 1 --robots 3 --team collaborative --plume-model physics --max-samples 8 "
          "--json --out " +
          (dir / "ev").string());
  ASSERT_EQ(r.code, 0) << r.err;
  j = json::parse(r.out);
  EXPECT_EQ(j["team"]["robots"], 3);
  EXPECT_EQ(j["team"]["strategy"], "collaborative");
  EXPECT_LE(j["overall"]["median_samples"].get<double>(), 3 * 8);
  r = run("localize " + map + " --source 4.5,0.5 --robots 2 --team swarm");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--team"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.5,0.5 --robots 2 --method surge-cast");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--robots"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.5,0.5 --robots 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--robots"), std::string::npos) << r.err;
}

TEST_F(SteCli, BadInputExitsTwoWithAClearMessage) {
  const std::string map = write_map();
  CliResult r = run("localize " + map + " --source 2.7,1.5 --plume-model physics");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("inside obstacles[0]"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --start 9,1 --plume-model physics");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--start"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("outside the arena"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model kriging --json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown plume model 'kriging'"), std::string::npos) << r.err;
  EXPECT_FALSE(json::parse(r.out)["ok"].get<bool>());
  r = run("localize " + map + " --source 4.2,1.3 --plume-model surrogate --cnn " +
          (dir / "missing.pkcnn").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("missing.pkcnn not found"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model physics --reward greedy");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--reward: unknown reward 'greedy'"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model physics --candidates rooms");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--candidates: unknown candidates 'rooms' (lattice, floor or auto)"),
            std::string::npos)
      << r.err;
  r = run("localize " + map +
          " --source 4.2,1.3 --plume-model physics --candidates floor --floor-spacing -1");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--floor-spacing: must be a finite number more than 0"), std::string::npos)
      << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model physics --seen-mass 2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--seen-mass:"), std::string::npos) << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model physics --diffusivity 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--diffusivity: must be a finite number more than 0"), std::string::npos)
      << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model physics --lattice 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--lattice: must be a whole number from 1 to 20, got 0"), std::string::npos)
      << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model physics --source-cell 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--source-cell: must be a finite number more than 0"), std::string::npos)
      << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model gaussian --source-cell 0.2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--source-cell: only the surrogate and physics"), std::string::npos)
      << r.err;
  r = run("localize " + map + " --source 4.2,1.3 --plume-model physics --sigma-std 2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--sigma-std: only the surrogate"), std::string::npos) << r.err;
  r = run("evaluate --map-dir " + (dir / "nowhere").string() + " --plume-model physics");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("is not a directory"), std::string::npos) << r.err;
}

TEST_F(SteCli, EvaluateWritesEverythingAndIgnoresThreadCount) {
  write_map();
  const std::string maps = (dir / "maps").string();
  CliResult r =
      run("evaluate --map-dir " + maps +
          " --runs 2 --threads 1 --plume-model physics --json --out " + (dir / "e1").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["overall"]["runs"].get<int>(), 4);
  for (const char* f : {"runs.csv", "summary.json", "boxplot-error.png", "boxplot-samples.png",
                        "trajectories/small.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "e1" / f)) << f;
  r = run("evaluate --map-dir " + maps + " --runs 2 --threads 2 --plume-model physics --out " +
          (dir / "e2").string());
  ASSERT_EQ(r.code, 0) << r.err;
  // The same bytes whatever the threads: the measured times are in timings.csv and timings.json.
  EXPECT_EQ(slurp(dir / "e1" / "runs.csv"), slurp(dir / "e2" / "runs.csv"));
  EXPECT_EQ(slurp(dir / "e1" / "summary.json"), slurp(dir / "e2" / "summary.json"));
  const json timings = json::parse(slurp(dir / "e2" / "timings.json"));
  EXPECT_EQ(timings["threads"].get<int>(), 2);
  EXPECT_EQ(timings["maps"].size(), 1u);
  EXPECT_NE(
      slurp(dir / "e2" / "timings.csv").find("map,source_index,run,compute_s,median_step_s\n"),
      std::string::npos);
}

// Issue 18: every success rate has its 95 % interval, and --seeds K pools K seeds' runs, the
// first of which are the --seed run's own.
TEST_F(SteCli, EvaluateGivesIntervalsAndPoolsSeeds) {
  write_map();
  const std::string maps = (dir / "maps").string();
  CliResult one = run("evaluate --map-dir " + maps +
                      " --runs 1 --plume-model physics --json --out " + (dir / "s1").string());
  ASSERT_EQ(one.code, 0) << one.err;
  CliResult three =
      run("evaluate --map-dir " + maps + " --runs 1 --seeds 3 --plume-model physics --json --out " +
          (dir / "s3").string());
  ASSERT_EQ(three.code, 0) << three.err;
  const json j = json::parse(three.out);
  EXPECT_EQ(j["seeds"].get<int>(), 3);
  EXPECT_EQ(j["overall"]["runs"].get<int>(),
            3 * json::parse(one.out)["overall"]["runs"].get<int>());
  const json ci = j["overall"]["success_0_5m_ci95"];
  const double rate = j["overall"]["success_0_5m"].get<double>();
  EXPECT_LE(ci[0].get<double>(), rate);
  EXPECT_GE(ci[1].get<double>(), rate);
  EXPECT_LT(ci[1].get<double>() - ci[0].get<double>(), 1.0);
  const std::string csv = slurp(dir / "s3" / "runs.csv");
  EXPECT_NE(csv.find(",gsl_bench,seed\n"), std::string::npos);
  // Each source's first seed-1 run is the single-seed evaluation's run.
  std::istringstream a(slurp(dir / "s1" / "runs.csv")), b(csv);
  std::string la, lb;
  std::getline(a, la);
  std::getline(b, lb);
  ASSERT_TRUE(std::getline(a, la) && std::getline(b, lb));
  auto first_ten_cells = [](const std::string& line) {  // the run, its source, start, estimate
    std::string out;
    int commas = 0;
    for (const char c : line) {
      if (c == ',' && ++commas == 10) break;
      out += c;
    }
    return out;
  };
  EXPECT_EQ(first_ten_cells(lb), first_ten_cells(la));
  EXPECT_EQ(lb.substr(lb.rfind(',') + 1), "1");
  const CliResult none =
      run("evaluate --map-dir " + maps + " --seeds 0 --out " + (dir / "s0").string());
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("--seeds"), std::string::npos) << none.err;
}

// The robot's gas sensor is a preset, its anemometer and position have noise settings; a bad
// one is refused naming the flag (and, for the gas sensor, the presets).
TEST_F(SteCli, WorldSensorPresetsAndRefusals) {
  const std::string map = write_map();
  CliResult r = run("localize " + map +
                    " --source 1.5,1 --plume-model physics --gas-sensor mox-fast --json --out " +
                    (dir / "mox").string());
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("localize " + map + " --source 1.5,1 --plume-model physics --gas-sensor tgs9999 --out " +
          (dir / "bad").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--gas-sensor"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("infrared"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
  for (const std::string bad : {"--baseline nan", "--wind-noise north", "--wind-noise -5",
                                "--position-noise -1", "--position-noise north"}) {
    r = run("localize " + map + " --source 1.5,1 --plume-model physics " + bad + " --out " +
            (dir / "refused").string());
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "refused")) << bad;
  }
  // The stop is a setting: seed 000's 20 s at 1 Hz make the mission longer than 5 s at 10 Hz
  // (the thesis's protocol: every stop lasts --stop-s; the default's adaptive stops end sooner).
  auto mission = [&](const std::string& stop, const std::string& out) {
    const CliResult m =
        run("localize " + map + " --source 1.5,1 --plume-model physics --protocol thesis " + stop +
            " --max-samples 1 --json --out " + (dir / out).string());
    EXPECT_EQ(m.code, 0) << m.err;
    return json::parse(m.out)["mission_s"].get<double>();
  };
  EXPECT_NEAR(mission("--stop-s 20 --stop-rate 1", "long"), 20.0, 1e-6);  // one stop, no travel
  EXPECT_NEAR(mission("", "short"), 5.0, 1e-6);
  EXPECT_NEAR(mission("--adaptive-stops true", "adaptive"), 1.0,
              1e-6);  // clean air: settled at once
  // Each step reports the anemometer's wind and the position the robot recorded.
  r = run("localize " + map +
          " --source 1.5,1 --plume-model physics --wind-noise table35 --position-noise gps "
          "--max-samples 3 --json --out " +
          (dir / "noisy").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json step = json::parse(slurp(dir / "noisy" / "run.json"))["steps"][0];
  EXPECT_EQ(step["wind"].size(), 2u);
  EXPECT_NE(step["recorded_position"], step["position"]);
}

TEST_F(SteCli, DemoRunsAndSaysWhereThePicturesAre) {
  const CliResult r = run("demo --plume-model physics --out " + (dir / "demo").string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("pictures:"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "demo" / "trajectory.png"));
}

// Issue 48: `evaluate --replays` records every run's replay, linked from report.html (as a script
// a file:// page may load), and `plumekit replay` draws one; the results are those without it.
TEST_F(SteCli, EvaluateReplaysEveryRunLinkedFromTheReport) {
  write_map();
  const std::string maps = (dir / "maps").string();
  const std::string common =
      " --plume-model gaussian --max-samples 5 --max-steps 12 --runs 1 --method ste,zigzag";
  CliResult r =
      run("evaluate --map-dir " + maps + common + " --replays --out " + (dir / "with").string());
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("evaluate --map-dir " + maps + common + " --out " + (dir / "without").string());
  ASSERT_EQ(r.code, 0) << r.err;
  for (const std::string m : {"ste", "zigzag"})
    for (const char* f : {"runs.csv", "summary.json", "tracks.json"})
      EXPECT_EQ(slurp(dir / "with" / m / f), slurp(dir / "without" / m / f)) << m << ": " << f;
  EXPECT_FALSE(std::filesystem::exists(dir / "without" / "ste" / "replays"));
  const json page = report_page_data(dir / "with" / "report.html");
  ASSERT_EQ(page["replays"].size(), 4u);  // 2 methods x 2 sources
  EXPECT_EQ(page["replays"][0], "ste/replays/small-s0-r0");
  EXPECT_EQ(page["replays"][3], "zigzag/replays/small-s1-r0");
  for (const auto& link : page["replays"]) {
    const std::filesystem::path folder = dir / "with" / link.get<std::string>();
    const std::string replay = slurp(folder / "replay.json");
    EXPECT_EQ(slurp(folder / "replay.js"), "plumekitReplay(" + replay + ");\n") << folder;
    EXPECT_EQ(json::parse(replay)["format"], "plumekit-replay/1");
  }
  // A method's own report links its own folder's replays.
  EXPECT_EQ(report_page_data(dir / "with" / "zigzag" / "report.html")["replays"][1],
            "replays/small-s1-r0");
  EXPECT_FALSE(report_page_data(dir / "without" / "report.html").contains("replays"));
  r = run("replay " + (dir / "with" / "zigzag" / "replays" / "small-s1-r0").string() +
          " --at 5 --out " + (dir / "frame.png").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "frame.png"));
}

// Issue "plumekit from Python, and on many machines": `evaluate --shard K/N` parts joined by
// `evaluate merge` give a single run's runs.csv, summary.json and box plots, byte for byte.
class SteShards : public SteCli {
 protected:
  // Two maps, 2 + 3 sources: 3 parts split both maps and 2 parts split between them.
  std::string write_maps() {
    write_map();
    std::string second = kSmallMap;
    second.replace(second.find("\"small\""), 7, "\"small-b\"");
    second.replace(second.find("[[4.5, 0.5], [1.5, 0.7]]"), 24,
                   "[[4.5, 0.5], [1.5, 0.7], [5.2, 2.4]]");
    std::ofstream(dir / "maps" / "small-b.json") << second;
    return (dir / "maps").string();
  }
  static constexpr const char* kFast = " --plume-model gaussian --runs 1 --max-samples 6";

  // Runs the K/N parts into DIR/NAME-K; the folders' names, space-separated.
  std::string run_parts(const std::string& maps, int n, const std::string& name,
                        const std::string& extra = "") {
    std::string folders;
    for (int k = 0; k < n; ++k) {
      const std::string out = (dir / (name + "-" + std::to_string(k))).string();
      const CliResult r =
          run("evaluate --map-dir " + maps + kFast + extra + " --threads 1" + " --shard " +
              std::to_string(k) + "/" + std::to_string(n) + " --out " + out);
      EXPECT_EQ(r.code, 0) << r.err;
      folders += " " + out;
    }
    return folders;
  }
};

TEST_F(SteShards, MergedPartsAreTheSingleRunByteForByte) {
  const std::string maps = write_maps();
  // The last: a plume tracker's runs, with the source box and the distance overhead (issue 20).
  int case_number = 0;
  for (const auto& [n, extra] : {std::pair<int, std::string>{2, ""},
                                 {3, " --seeds 2"},
                                 {2, " --method zigzag --max-steps 20"}}) {
    const std::string tag = std::to_string(n) + "-" + std::to_string(case_number++);
    const CliResult one = run("evaluate --map-dir " + maps + kFast + extra + " --threads 2 --out " +
                              (dir / ("one-" + tag)).string());
    ASSERT_EQ(one.code, 0) << one.err;
    const std::string parts = run_parts(maps, n, "part" + tag, extra);
    EXPECT_TRUE(std::filesystem::exists(dir / ("part" + tag + "-0") / "part.json"));
    const CliResult merged =
        run("evaluate merge" + parts + " --json --out " + (dir / ("merged-" + tag)).string());
    ASSERT_EQ(merged.code, 0) << merged.err;
    EXPECT_EQ(json::parse(merged.out)["parts"].get<int>(), n);
    for (const char* f : {"runs.csv", "summary.json", "boxplot-error.png", "boxplot-samples.png",
                          "tracks.json", "report.html"})
      EXPECT_EQ(slurp(dir / ("merged-" + tag) / f), slurp(dir / ("one-" + tag) / f))
          << f << " of " << n << " parts";
    // The timings have every run, in the same order, with the part's measured times.
    const std::string a = slurp(dir / ("merged-" + tag) / "timings.csv"),
                      b = slurp(dir / ("one-" + tag) / "timings.csv");
    EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), std::count(b.begin(), b.end(), '\n'));
    const json t = json::parse(slurp(dir / ("merged-" + tag) / "timings.json"));
    EXPECT_EQ(t["parts"].size(), static_cast<std::size_t>(n));
  }
}

TEST_F(SteShards, MergeRefusesBadPartsAndWritesNothing) {
  const std::string maps = write_maps();
  const std::string p = (dir / "p").string();
  run_parts(maps, 3, "p");
  const std::string out = (dir / "merged").string();
  auto refused = [&](const std::string& parts, const std::string& message) {
    const CliResult r = run("evaluate merge " + parts + " --out " + out);
    EXPECT_EQ(r.code, 2) << parts;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << parts;
  };
  refused(p + "-0 " + p + "-1", "part 2 of 3 is missing");
  refused(p + "-0 " + p + "-1 " + p + "-1 " + p + "-2", "part 1 of 3 is given twice");
  refused(p + "-0 " + maps, "holds no part.json");
  // Another option (in any part) is another evaluation.
  const CliResult other = run("evaluate --map-dir " + maps + kFast +
                              " --alpha 0.3 --shard 2/3 --out " + (dir / "other").string());
  ASSERT_EQ(other.code, 0) << other.err;
  refused(p + "-0 " + p + "-1 " + (dir / "other").string(), "its options --alpha is \"0.3\", ");
  // A damaged file, and a damaged part.json.
  std::filesystem::copy(p + "-2", dir / "bad", std::filesystem::copy_options::recursive);
  std::string csv = slurp(dir / "bad" / "runs.csv");
  csv[csv.size() / 2] = csv[csv.size() / 2] == '1' ? '2' : '1';
  std::ofstream(dir / "bad" / "runs.csv") << csv;
  refused(p + "-0 " + p + "-1 " + (dir / "bad").string(), "runs.csv: does not match its checksum");
  std::filesystem::copy(p + "-2/runs.csv", dir / "bad" / "runs.csv",
                        std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "bad" / "tracks.json", std::ios::app) << " ";
  refused(p + "-0 " + p + "-1 " + (dir / "bad").string(),
          "tracks.json: does not match its checksum");
  std::filesystem::remove(dir / "bad" / "tracks.json");
  refused(p + "-0 " + p + "-1 " + (dir / "bad").string(), "tracks.json");
  std::filesystem::copy(p + "-2/tracks.json", dir / "bad" / "tracks.json");
  const std::string part = slurp(p + "-2/part.json");
  std::ofstream(dir / "bad" / "part.json") << part.substr(0, part.size() / 2);
  refused(p + "-0 " + p + "-1 " + (dir / "bad").string(), "not a well-formed evaluate part");
  std::string edited = part;
  edited.replace(edited.find("\"wall_s\": "), 10, "\"wall_s\": 7");
  std::ofstream(dir / "bad" / "part.json") << edited;
  refused(p + "-0 " + p + "-1 " + (dir / "bad").string(), "does not match its own checksum");
  const CliResult bad = run("evaluate --map-dir " + maps + " --shard 3/3 --out " + out);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--shard: expected K/N with 0 <= K < N"), std::string::npos) << bad.err;
  // The good parts merge.
  EXPECT_EQ(run("evaluate merge " + p + "-0 " + p + "-2 " + p + "-1 --out " + out).code, 0);
}

// Issue 44: runs.csv and timings.csv quote a map name holding a comma, a quote or a line break
// (RFC 4180), python's csv module reads them back, and `evaluate merge` joins such parts.
TEST_F(SteShards, AMapNameWithACommaQuoteOrLineBreakIsQuotedAndReadBack) {
  const std::string maps = write_maps();
  std::string second = slurp(dir / "maps" / "small-b.json");
  second.replace(second.find("\"small-b\""), 9, "\"small, \\\"b\\\"\\nhall\"");
  std::ofstream(dir / "maps" / "small-b.json") << second;
  const CliResult one =
      run("evaluate --map-dir " + maps + kFast + " --out " + (dir / "one").string());
  ASSERT_EQ(one.code, 0) << one.err;
  const std::string csv = slurp(dir / "one" / "runs.csv");
  EXPECT_NE(csv.find("\n\"small, \"\"b\"\"\nhall\",0,0,"), std::string::npos) << csv;
  EXPECT_NE(slurp(dir / "one" / "timings.csv").find("\n\"small, \"\"b\"\"\nhall\",0,0,"),
            std::string::npos);
  // The project's python reader (scripts/evaluation_runs.py): every row whole, the name intact.
  std::ofstream(dir / "check.py") << "import sys\n"
                                     "sys.path.insert(0, sys.argv[1])\n"
                                     "from evaluation_runs import read_runs\n"
                                     "runs = read_runs(sys.argv[2])\n"
                                     "assert len(runs) == 5, len(runs)\n"
                                     "assert all(None not in r and r['stopped_by'] for r in runs)\n"
                                     "names = sorted({r['map'] for r in runs})\n"
                                     "assert names == ['small', 'small, \"b\"\\nhall'], names\n";
  const int py =
      std::system(("/usr/bin/python3 " + (dir / "check.py").string() + " " +
                   std::string(PLUMEKIT_SOURCE_DIR) + "/scripts " + (dir / "one").string())
                      .c_str());
  EXPECT_EQ(py, 0);
  const CliResult merged =
      run("evaluate merge" + run_parts(maps, 3, "p") + " --out " + (dir / "merged").string());
  ASSERT_EQ(merged.code, 0) << merged.err;
  for (const char* f : {"runs.csv", "summary.json"})
    EXPECT_EQ(slurp(dir / "merged" / f), slurp(dir / "one" / f)) << f;
}

// Issue 44: the physics model's candidate grid is refused before any work when its memory would
// pass the limit (1.6 million cells take about 390 MB at their peak), naming the flags that fit.
TEST_F(SteCli, APhysicsSourceGridOverTheMemoryLimitIsRefusedNamingTheFlag) {
  const CliResult r = run("localize " + std::string(PLUMEKIT_DATA_DIR) +
                          "/maps/cluttered-1.json --source 1.5,1 --plume-model physics "
                          "--source-cell 0.005 --max-memory 300M --out " +
                          (dir / "out").string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("the source grid of 1.6e+06 cells of 0.005 m needs about"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("use a larger --source-cell ("), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("m fits), or raise the limit with --max-memory "), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

// Issue 46: the default surrogate (the hybrid) runs on a map of any size, warning outside its
// training sizes; the thesis's fixed-grid model, named, refuses another size saying what to type.
TEST_F(SteCli, TheDefaultSurrogateTakesAnyMapAndTheThesisModelSaysWhatToType) {
  const std::string map = write_map();  // 6 x 3 m
  CliResult r = run("localize " + map + " --source 4.2,1.3 --max-samples 3 --json --out " +
                    (dir / "l").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("the map is 6 x 3 m; the model was trained on maps 6.1-30 m wide"),
            std::string::npos)
      << r.err;
  EXPECT_NE(nlohmann::json::parse(r.out)["cnn"].get<std::string>().find("plume-unet-v3.pkcnn"),
            std::string::npos)
      << r.out;
  r = run("localize " + map + " --source 4.2,1.3 --cnn thesis");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("works only on maps of 10 x 4 m"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("map \"small\" is 6 x 3 m"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("use the default model (--cnn hybrid)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--plume-model physics"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("feature contract"), std::string::npos) << r.err;
  r = run("predict " + map + " --source 4.2,1.3 --cnn thesis --out " + (dir / "p").string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("plume-unet.pkcnn: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--cnn hybrid"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("--plume-model"), std::string::npos) << "predict has no such flag";
  EXPECT_FALSE(std::filesystem::exists(dir / "p"));
}

// Issue 44: --help marks --source as required; --tunnel names the part that is wrong.
TEST_F(SteCli, HelpAndTunnelMessagesSayWhatIsWrong) {
  CliResult r = run("localize --help");
  ASSERT_EQ(r.code, 0);
  const std::size_t at = r.out.find("  --source ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_NE(r.out.substr(at, r.out.find('\n', at) - at).find("REQUIRED"), std::string::npos)
      << r.out;
  r = run("localize " + write_map() + " --plume-model physics");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--source is required"), std::string::npos) << r.err;
  const std::pair<const char*, const char*> parts[] = {{"0.5,4,2", "--tunnel's length (L of"},
                                                       {"10,0.5,2", "--tunnel's width (W of"},
                                                       {"10,4,50", "--tunnel's height (H of"}};
  for (const auto& [size, part] : parts) {
    r = run(std::string("localize tunnel --tunnel ") + size);
    EXPECT_EQ(r.code, 2) << size;
    EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace plumekit::test
