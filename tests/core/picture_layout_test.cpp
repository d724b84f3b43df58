// Every picture plumekit draws, on a tall, a wide and a square map at 20, 100
// and 400 px/m: no text box may leave the image or overlap another. Set
// PLUMEKIT_PICTURE_DIR to also write each picture there, to look at them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "cfd/flow_render.hpp"
#include "core/error.hpp"
#include "map/map_render.hpp"
#include "planner/plan_render.hpp"
#include "run/render.hpp"
#include "run/tunnel_report.hpp"

namespace plumekit {
namespace {

// What is wrong with a picture's text layout; empty when it reads.
std::vector<std::string> layout_problems(const Picture& p) {
  std::vector<std::string> problems;
  const cv::Rect image(0, 0, p.image.cols, p.image.rows);
  auto str = [](const cv::Rect& r) {
    std::ostringstream s;
    s << r;
    return s.str();
  };
  for (std::size_t a = 0; a < p.text_boxes.size(); ++a) {
    const cv::Rect& r = p.text_boxes[a];
    if ((r & image) != r) problems.push_back("box " + str(r) + " leaves the image " + str(image));
    for (std::size_t b = a + 1; b < p.text_boxes.size(); ++b)
      if ((r & p.text_boxes[b]).area() > 0)
        problems.push_back("boxes " + str(r) + " and " + str(p.text_boxes[b]) + " overlap");
  }
  return problems;
}

struct Shape {
  const char* name;
  double width, height;
};
const Shape kShapes[] = {{"tall", 2.0, 10.0}, {"wide", 10.0, 2.0}, {"square", 5.0, 5.0}};
const double kScales[] = {20.0, 100.0, 400.0};

// An arena with one obstacle and two sources, scaled to its shape.
Map test_map(const Shape& s) {
  Map m = default_arena(s.width, s.height);
  m.name = std::string(s.name) + "-arena";
  const double cx = 0.5 * s.width, cy = 0.5 * s.height;
  const double hx = 0.15 * s.width, hy = 0.15 * s.height;
  m.obstacles.push_back(
      {{cx - hx, cy - hy}, {cx + hx, cy - hy}, {cx + hx, cy + hy}, {cx - hx, cy + hy}});
  m.sources = {{0.2 * s.width, 0.2 * s.height}, {0.8 * s.width, 0.8 * s.height}};
  return m;
}

// A uniform wind along x (zero in obstacle cells).
cfd::WindField test_wind(const Map& map) {
  const GridShape g = GridShape::with_cell(map.width, map.height, 0.1);
  std::vector<double> fu((g.nx + 1) * g.ny, 1.0), fv(g.nx * (g.ny + 1), 0.0), p(g.size(), 0.0);
  std::vector<std::uint8_t> solid(g.size(), 0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      solid[g.index(i, j)] = map.obstacle_at(g.centre(i, j)) >= 0;
  return cfd::WindField(g, fu, fv, p, solid);
}

// A plume-like field that falls off with distance from `source`.
Grid<double> test_plume(const Map& map, Vec2 source) {
  Grid<double> f(GridShape{64, 64, map.width, map.height}, 0.0);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      f(i, j) = 10.0 * std::exp(-norm(f.shape.centre(i, j) - source));
  return f;
}

run::LocalizationResult test_run(const Map& map) {
  run::LocalizationResult r;
  r.start = {0.1 * map.width, 0.9 * map.height};
  r.estimate = {0.25 * map.width, 0.25 * map.height};
  Vec2 at = r.start;
  for (int k = 0; k < 5; ++k) {
    run::Step s;
    const Vec2 next{at.x + 0.03 * map.width, at.y - 0.12 * map.height};
    s.path_in = {at, next};
    s.position = next;
    s.value = 2.0 * k;
    r.steps.push_back(s);
    at = next;
  }
  r.samples = 5;
  r.distance_m = 3.0;
  r.stopped_by = "entropy";
  r.posterior.marginal = test_plume(map, r.estimate);
  return r;
}

run::BoxPlot test_box_plot(int groups) {
  run::BoxPlot p;
  p.title = "STE (surrogate) localization error per test map";
  p.y_label = "error [m]";
  p.reference = 0.5;
  p.reference_label = "success radius 0.5 m";
  for (int g = 0; g < groups; ++g) {
    p.names.push_back("cluttered-" + std::to_string(g));
    p.groups.push_back({0.1 * g, 0.3, 0.5 + g, 1.0, 2.5, 9.0});
  }
  return p;
}

void look(const Picture& p, const std::string& name) {
  const char* dir = std::getenv("PLUMEKIT_PICTURE_DIR");
  if (dir) write_png(p, std::filesystem::path(dir) / (name + ".png"));
  for (const std::string& problem : layout_problems(p))
    ADD_FAILURE() << name << ": " << problem;
  EXPECT_FALSE(p.text_boxes.empty()) << name;
}

TEST(PictureLayout, MapWindPlumeAndPlanReadAtEveryShapeAndScale) {
  for (const Shape& s : kShapes)
    for (double px : kScales) {
      const Map map = test_map(s);
      const RenderOptions o{px};
      const std::string tag = std::string(s.name) + "-" + std::to_string(int(px));
      look(render_map(map, o), "map-" + tag);
      look(render_map(map, o, 0.5), "map-cells-" + tag);
      look(cfd::draw_wind(map, test_wind(map), o), "wind-" + tag);
      const Grid<double> mean = test_plume(map, map.sources[0]);
      const Grid<double> zero(mean.shape, 0.0);  // an all-zero std
      look(draw_plume(map, mean, zero, map.sources[0], "filament plume", "", o), "plume-" + tag);

      const planner::FreeSpace space(map, 0.15, 8);
      planner::PlanResult plan;
      plan.requested_start = {0.0, 0.0};
      plan.start = {0.2, 0.2};
      plan.start_moved = true;
      plan.goal = {0.9 * s.width, 0.9 * s.height};
      plan.requested_goal = plan.goal;
      plan.path = {plan.start, {0.2, 0.9 * s.height}, plan.goal};
      plan.length = 12.0;
      look(planner::draw_plan(map, space, plan, "vg", o), "plan-" + tag);
    }
}

TEST(PictureLayout, MapReadsAtTheLargestAcceptedScale) {
  for (const Shape& s : kShapes)
    look(render_map(test_map(s), RenderOptions{1000.0}), "map-" + std::string(s.name) + "-1000");
}

TEST(PictureLayout, TrajectoryAndPosteriorReadAtEveryShapeAndScale) {
  for (const Shape& s : kShapes)
    for (double px : kScales) {
      const Map map = test_map(s);
      const RenderOptions o{px};
      const std::string tag = std::string(s.name) + "-" + std::to_string(int(px));
      const run::LocalizationResult r = test_run(map);
      run::RunRecord record;
      record.result = r;
      record.source = map.sources[1];
      record.source_index = 1;
      record.run = 2;
      const run::RunToDraw run = run::run_to_draw(record, "surrogate", "median run of 10");
      const Picture t = run::draw_trajectory(map, test_plume(map, record.source), run, o);
      look(t, "trajectory-" + tag);
      look(run::draw_posterior(map, run, o), "posterior-" + tag);
    }
}

TEST(PictureLayout, BoxPlotsReadWithFewAndManyGroups) {
  for (int groups : {1, 3, 40})
    look(run::draw_box_plot(test_box_plot(groups)), "boxplot-" + std::to_string(groups));
}

// The tunnel's run picture (issue 44): both panels carry axes in metres, tick labels under and
// left of each panel, at the thesis's tunnel, a long one and the smallest accepted.
TEST(PictureLayout, TunnelRunHasAxesInMetres) {
  for (const Vec3 size : {Vec3{10.0, 4.0, 2.0}, Vec3{200.0, 50.0, 20.0}, Vec3{1.0, 1.0, 1.0}}) {
    world::Tunnel t;
    t.length = size.x, t.width = size.y, t.height = size.z;
    run::TunnelRun r;
    r.source = {0.2 * size.x, 0.5 * size.y, 0.5 * size.z};
    r.start = {0.8 * size.x, 0.3 * size.y, 0.4 * size.z};
    r.estimate = {0.25 * size.x, 0.55 * size.y, 0.5 * size.z};
    for (const Vec3& p : {r.start, r.estimate}) {
      run::TunnelStep step;
      step.position = p;
      step.phase = "sample";
      r.steps.push_back(step);
    }
    const std::string tag = "tunnel-" + std::to_string(static_cast<int>(size.x));
    const Picture p = run::draw_tunnel_run(r, t, "ste-3d: error 0.3 m, " + tag);
    look(p, tag);
    // The upper panel is p.arena; the lower one lies below it, as wide.
    int below = 0, left = 0;
    for (const cv::Rect& b : p.text_boxes) {
      below += b.y >= p.arena.br().y && b.y < p.arena.br().y + 20 && b.x >= p.arena.x - 20 &&
               b.br().x <= p.arena.br().x + 20;
      left += b.br().x <= p.arena.x && b.y >= p.arena.y - 10 && b.br().y <= p.arena.br().y + 10;
    }
    EXPECT_GE(below, 2) << tag << ": x tick labels under the panel";
    EXPECT_GE(left, 2) << tag << ": y tick labels left of the panel";
  }
}

TEST(PictureLayout, TheCheckCatchesOverlapsAndBoxesOutsideTheImage) {
  Picture p = render_map(test_map(kShapes[0]), RenderOptions{100.0});
  ASSERT_TRUE(layout_problems(p).empty());
  Picture overlapping = p;
  overlapping.text_boxes.push_back(p.text_boxes.front() + cv::Point(2, 1));
  EXPECT_EQ(layout_problems(overlapping).size(), 1u);
  Picture outside = p;
  outside.text_boxes.push_back(cv::Rect(p.image.cols - 5, 0, 10, 4));
  EXPECT_FALSE(layout_problems(outside).empty());
}

TEST(PictureLayout, TitlesNameTheRunTheyDraw) {
  // The run's own numbers: source S1, run 2, its error (estimate to source).
  const Map map = test_map(kShapes[2]);
  run::RunRecord record;
  record.result = test_run(map);
  record.source = map.sources[1];
  record.source_index = 1;
  record.run = 2;
  const run::RunToDraw run = run::run_to_draw(record, "surrogate");
  EXPECT_EQ(run.result, &record.result);
  EXPECT_EQ(run.source_index, 1);
  EXPECT_EQ(run.run, 2);
  // The title states the drawn run's own source, number and error (estimate to true source).
  const std::string title = run::trajectory_title(map, run);
  const double error = norm(record.result.estimate - record.source);
  std::ostringstream expected;
  expected << "source S1 run 2: error " << std::fixed << std::setprecision(2) << error
           << " m, 5 samples";
  EXPECT_NE(title.find(expected.str()), std::string::npos) << title;
  EXPECT_EQ(title.find("median run"), std::string::npos) << title;
  EXPECT_NE(run::trajectory_title(map, run::run_to_draw(record, "surrogate", "median run of 9"))
                .find("(median run of 9)"),
            std::string::npos);
  // A single run's source index is looked up among the map's sources.
  EXPECT_EQ(run::run_to_draw(map, record.result, map.sources[1], "gaussian").source_index, 1);
  EXPECT_EQ(run::run_to_draw(map, record.result, {0.3, 0.3}, "gaussian").source_index, -1);
}

TEST(PictureLayout, PixelsPerMetreOutOfRangeIsRefused) {
  for (double bad : {10.0, 2000.0, std::nan("")}) {
    try {
      RenderOptions{bad}.validate();
      ADD_FAILURE() << bad;
    } catch (const OptionError& e) {
      EXPECT_EQ(e.field(), "render.px_per_m");
    }
  }
  EXPECT_NO_THROW(RenderOptions{20.0}.validate());
  EXPECT_NO_THROW(RenderOptions{400.0}.validate());
}

}  // namespace
}  // namespace plumekit
