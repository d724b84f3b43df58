// Planner benchmark: on the shipped maps, the nine test maps and a dense seeded map of 96
// obstacle vertices, prints the visibility graph's build time, the median VG
// query time, and how long OMPL's RRT* and PRM* take to return a path within
// 1 % of the VG optimum (or how close they got within the budget).
//
//   ./build/bench/planner_bench [--queries 2000] [--ompl-queries 10] [--ompl-budget 2]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/random.hpp"
#include "core/statistics.hpp"
#include "map/map_json.hpp"
#include "planner/ompl_planner.hpp"
#include "planner/vg_planner.hpp"

namespace {

using namespace plumekit;
using namespace plumekit::planner;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// 15 obstacles in two rows (4 rectangles, 4 Ls, 7 Us, seeded jitter): 96 vertices.
Map dense_map() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<> jitter(-0.1, 0.1);
  Map m = default_arena();
  m.name = "dense";
  for (int k = 0; k < 15; ++k) {
    const double x = 0.5 + (k / 2) * 1.2 + jitter(rng), y = (k % 2 ? 2.3 : 0.5) + jitter(rng);
    const double w = 0.8, h = 1.1, t = 0.25;
    Polygon p;
    switch (k % 4) {
      case 0:
        p = {{0, 0}, {w, 0}, {w, h}, {0, h}};
        break;
      case 1:
        p = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, h}, {0, h}};
        break;
      default:
        p = {{0, 0}, {w, 0}, {w, t}, {t, t}, {t, h - t}, {w, h - t}, {w, h}, {0, h}};
    }
    if (k % 3 == 2)
      for (Vec2& v : p)
        v.x = w - v.x;  // mirrored: Us open both ways
    for (Vec2& v : p)
      v = {v.x + x, v.y + y};
    m.obstacles.push_back(p);
  }
  validate_map(m, "dense");
  return m;
}

struct Query {
  Vec2 from, to;
  double length;
};

struct Args {
  int queries = 2000, ompl_queries = 10;
  double ompl_budget_s = 2.0;
};

std::vector<Map> bench_maps() {
  std::vector<std::filesystem::path> files;
  for (const char* folder : {PLUMEKIT_DATA_DIR "/maps", PLUMEKIT_DATA_DIR "/test-maps"}) {
    std::vector<std::filesystem::path> here;
    for (const auto& e : std::filesystem::directory_iterator(folder))
      here.push_back(e.path());
    std::sort(here.begin(), here.end());
    files.insert(files.end(), here.begin(), here.end());
  }
  std::vector<Map> maps;
  for (const auto& f : files)
    maps.push_back(read_map(f));
  maps.push_back(dense_map());
  return maps;
}

// Seeded random free pairs that the VG can join.
std::vector<Query> random_queries(const Map& map, const VisibilityGraphPlanner& vg, int count,
                                  unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<Query> queries;
  while (static_cast<int>(queries.size()) < count) {
    const Vec2 a{uniform(rng, 0.0, map.width), uniform(rng, 0.0, map.height)};
    const Vec2 b{uniform(rng, 0.0, map.width), uniform(rng, 0.0, map.height)};
    if (map.obstacle_at(a) >= 0 || map.obstacle_at(b) >= 0) continue;
    try {
      queries.push_back({a, b, vg.plan(a, b).length});
    } catch (const InputError&) {
    }
  }
  return queries;
}

// One table row: build time, query time quantiles, nodes expanded. Returns the
// queries and the median query time (us), the baseline of the OMPL table.
std::pair<std::vector<Query>, double> bench_vg(const Map& map, std::size_t index,
                                               const PlannerOptions& options, int n_queries) {
  std::vector<double> builds;
  for (int k = 0; k < 5; ++k) {
    const auto t0 = Clock::now();
    VisibilityGraphPlanner vg(map, options);
    builds.push_back(seconds_since(t0) * 1e3);
  }
  const VisibilityGraphPlanner vg(map, options);
  std::vector<Query> queries =
      random_queries(map, vg, n_queries, 1000 + static_cast<unsigned>(index));
  std::vector<double> times;
  double expanded = 0.0;
  for (int run = 0; run < 3; ++run)
    for (const Query& q : queries) {
      const auto t0 = Clock::now();
      const PlanResult r = vg.plan(q.from, q.to);
      times.push_back(seconds_since(t0) * 1e6);
      expanded += r.expanded;
    }
  std::printf("%-12s %5zu %6d %6zu %9.2f %11.2f %11.2f %9.1f\n", map.name.c_str(),
              vertex_count(map), vg.graph().node_count(), vg.graph().edge_count(), median(builds),
              median(times), percentile(times, 0.9), expanded / static_cast<double>(times.size()));
  return {std::move(queries), median(times)};
}

// OMPL: doubling iteration budgets (with path simplification) until the path is
// within 1 % of the VG optimum, or the time budget is spent. One table row.
void bench_ompl(const Map& map, PlannerKind kind, const std::vector<Query>& queries,
                const PlannerOptions& options, double budget_s, double vg_median_us) {
  std::vector<double> times, iters, ratios;
  int reached = 0;
  for (const Query& q : queries) {
    double spent = 0.0, best = 1e300;
    for (int n = 100; spent < budget_s; n *= 2) {
      PlannerOptions o = options;
      o.ompl_iterations = n;
      o.ompl_time_limit_s = budget_s;
      const OmplPlanner planner(map, o, kind);
      const auto t0 = Clock::now();
      double length = 1e300;
      try {
        length = planner.plan(q.from, q.to).length;
      } catch (const InputError&) {
      }
      const double t = seconds_since(t0);
      spent += t;
      best = std::min(best, length / q.length);
      if (length <= 1.01 * q.length) {
        ++reached;
        times.push_back(t);
        iters.push_back(n);
        break;
      }
    }
    ratios.push_back(best);
  }
  std::printf("%-12s %-8s %5d/%-2zu %10.2f %10.0f %10.4f %9.0f\n", map.name.c_str(),
              to_string(kind), reached, queries.size(), median(times) * 1e3, median(iters),
              median(ratios), median(times) * 1e6 / vg_median_us);
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--queries")) args.queries = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--ompl-queries")) args.ompl_queries = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--ompl-budget")) args.ompl_budget_s = std::atof(argv[i + 1]);
  }
  const std::vector<Map> maps = bench_maps();
  PlannerOptions options;  // margin 0.15 m, 16-gon
  std::printf(
      "margin %.2f m, %d-gon inflation; %d VG queries per map (3 timed runs each), "
      "%d OMPL queries per map, OMPL budget %.1f s per query\n\n",
      options.margin, options.arc_segments, args.queries, args.ompl_queries, args.ompl_budget_s);
  std::printf("%-12s %5s %6s %6s %9s %11s %11s %9s\n", "map", "verts", "nodes", "edges", "build_ms",
              "query_med_us", "query_p90_us", "expanded");
  std::vector<std::vector<Query>> ompl_queries(maps.size());
  std::vector<double> vg_medians;
  for (std::size_t mi = 0; mi < maps.size(); ++mi) {
    auto [queries, vg_median] = bench_vg(maps[mi], mi, options, args.queries);
    vg_medians.push_back(vg_median);
    queries.resize(std::min<std::size_t>(queries.size(), args.ompl_queries));
    ompl_queries[mi] = std::move(queries);
  }
  std::printf(
      "\nOMPL, time to a path within 1%% of the VG optimum (simplified; median over "
      "queries);\n"
      "ratio: OMPL length / VG length where it stopped; x_vg_time: OMPL time / median VG "
      "query time\n");
  std::printf("%-12s %-8s %8s %10s %10s %10s %9s\n", "map", "planner", "reached", "median_ms",
              "iterations", "ratio", "x_vg_time");
  for (std::size_t mi = 0; mi < maps.size(); ++mi)
    for (PlannerKind kind : {PlannerKind::RRTstar, PlannerKind::PRMstar})
      bench_ompl(maps[mi], kind, ompl_queries[mi], options, args.ompl_budget_s, vg_medians[mi]);
  std::printf("\nworst median VG query: %.2f us\n",
              *std::max_element(vg_medians.begin(), vg_medians.end()));
  return 0;
}
