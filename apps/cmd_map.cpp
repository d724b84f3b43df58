// plumekit map validate | render | import-ros
#include <cmath>
#include <iomanip>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "apps/cli.hpp"
#include "apps/commands.hpp"
#include "core/error.hpp"
#include "core/option_check.hpp"
#include "core/output_target.hpp"
#include "map/connectivity.hpp"
#include "map/map_json.hpp"
#include "map/map_render.hpp"
#include "map/rasterize.hpp"
#include "map/ros_import.hpp"
#include "map/ros_import_report.hpp"

namespace plumekit::cli {

namespace {

using nlohmann::ordered_json;

// Resolution of the checks that need a grid (free share, inlet-to-outlet path).
constexpr double kCheckCell = 0.05;

// What validate reports. Warnings flag maps that are valid files but that
// no flow can pass through, which the flow and dataset commands refuse.
ordered_json map_summary(const Map& map, const std::string& file) {
  ordered_json j = map_to_json(map);
  j.erase("obstacles");
  j.erase("sources");
  ordered_json out{{"ok", true}, {"file", file}};
  out.update(j);
  out["obstacles"] = map.obstacles.size();
  out["obstacle_vertices"] = vertex_count(map);
  out["sources"] = map.sources.size();
  // A huge arena is checked on a coarser grid, so that validation stays quick and small.
  const MapGridCheck check = map_grid_check(map, kCheckCell);
  out["free_fraction"] = check.free_fraction;
  out["check_cell_m"] = check.cell;
  out["warnings"] = ordered_json::array();
  std::ostringstream cell;  // 2 significant digits: cells are extent / n, "5 cm", not "5.002 cm"
  cell << std::setprecision(2);
  if (check.cell < 1.0)
    cell << check.cell * 100 << " cm";
  else
    cell << check.cell << " m";
  if (check.coarsened)
    out["warnings"].push_back("the arena is too large to check at 5 cm cells; checked at " +
                              cell.str() + ", where passages narrower than that may look closed");
  const std::vector<MissedOpening> missed = check.inlet_reaches_outlet
                                                ? std::vector<MissedOpening>{}
                                                : openings_missed_by_grid(map, check.shape);
  if (!missed.empty()) {
    // The grid is at fault, not the map: it cannot tell whether air crosses.
    const MissedOpening& m = missed.front();
    std::ostringstream s;
    s << "no free path from the inlet to the outlet at " << cell.str() << " cells, which are too "
      << "coarse for this map: " << opening_name(map, m.index) << " is " << compact(m.length)
      << " m long, shorter than a cell, so no cell opens onto it; a check that sees it needs "
      << "cells of at most " << compact(m.length) << " m ("
      << compact(std::ceil(map.width / m.length) * std::ceil(map.height / m.length))
      << " cells; it takes at most " << compact(kMaxCheckCells) << ")";
    out["warnings"].push_back(s.str());
  } else if (!check.inlet_reaches_outlet) {
    out["warnings"].push_back("no free path from the inlet to the outlet at " + cell.str() +
                              " cells: the map cannot carry a flow");
    // Which region is sealed and how to open it, as import-ros says (its
    // first line repeats the warning above).
    const std::vector<std::string> advice =
        sealed_map_advice(map, free_regions(rasterize_labels(map, check.shape)), false, false);
    for (std::size_t k = 1; k < advice.size(); ++k)
      out["warnings"].push_back(advice[k]);
  }
  // A source that gas cannot leave is a valid point no run can find. Not on a
  // coarsened grid, where narrow passages may look closed.
  if (!check.coarsened && !map.sources.empty()) {
    const std::vector<bool> sealed =
        in_sealed_pocket(rasterize_labels(map, check.shape), map.sources);
    for (std::size_t k = 0; k < sealed.size(); ++k)
      if (sealed[k])
        out["warnings"].push_back("sources[" + std::to_string(k) + "] " +
                                  to_string(map.to_frame(map.sources[k])) + " " + kSealedPocket +
                                  " (checked at " + cell.str() +
                                  " cells); move it, or add an opening on the pocket's boundary");
  }
  return out;
}

void add_validate(CLI::App& map_cmd) {
  auto* cmd = map_cmd.add_subcommand(
      "validate", "Check a plumekit-map/2 (or /1) file; exit 2 naming the fault");
  auto path = std::make_shared<std::string>();
  add_map_argument(cmd, *path);
  add_common_flags(cmd);
  cmd->callback([path] {
    const Map map = read_map(*path);
    const ordered_json summary = map_summary(map, *path);
    std::ostringstream human;
    std::size_t inlets = 0;
    for (const Opening& o : map.openings)
      inlets += o.is_inlet();
    human << *path << ": valid " << summary["format"].get<std::string>() << " '" << map.name
          << "', " << map.width << " x " << map.height << " m, " << inlets
          << (inlets == 1 ? " inlet, " : " inlets, ") << map.openings.size() - inlets
          << (map.openings.size() - inlets == 1 ? " outlet, " : " outlets, ")
          << map.obstacles.size() << " obstacles (" << vertex_count(map) << " vertices), "
          << map.sources.size() << (map.sources.size() == 1 ? " source" : " sources");
    for (const auto& w : summary["warnings"])
      warn(w.get<std::string>());
    report(summary, human.str());
  });
}

void add_render(CLI::App& map_cmd) {
  auto* cmd = map_cmd.add_subcommand("render",
                                     "Draw a map to PNG: obstacles, inlet, outlet, sources, scale");
  struct Args {
    std::string map, out;
    RenderOptions render;
    double cells = 0.0;
  };
  auto a = std::make_shared<Args>();
  add_map_argument(cmd, a->map);
  cmd->add_option("--out,-o", a->out, "PNG file to write (new, or a picture plumekit drew)")
      ->required();
  bind_field(cmd, cmd->add_option("--px-per-m", a->render.px_per_m, "Pixels per metre"),
             "render.px_per_m")
      ->capture_default_str();
  cmd->add_option("--cells", a->cells,
                  "Also show the grid at this cell size (m), tinting the cells that count as solid")
      ->check(CLI::PositiveNumber);
  add_common_flags(cmd);
  cmd->callback([a] {
    const Map map = read_map(a->map);
    check_output_file(a->out, {a->map});
    const Picture picture = render_map(map, a->render, a->cells);
    write_png(picture, a->out);
    ordered_json j{{"ok", true},
                   {"map", a->map},
                   {"out", a->out},
                   {"width_px", picture.image.cols},
                   {"height_px", picture.image.rows},
                   {"arena_px",
                    {picture.arena.x, picture.arena.y, picture.arena.width, picture.arena.height}}};
    std::ostringstream human;
    human << "wrote " << a->out << " (" << picture.image.cols << " x " << picture.image.rows
          << " px)";
    report(j, human.str());
  });
}

// A --source or --start of import-ros (map frame), in the arena frame; refused
// naming the flag and the value, not the output file's key, when it lies off
// the imported map or in an obstacle.
Vec2 imported_point(const Map& map, const std::string& text, const std::string& flag) {
  const Vec2 p = map.from_frame(parse_point(text, flag));
  if (!map.in_arena(p)) {
    const Vec2 lo = map.to_frame({0.0, 0.0}), hi = map.to_frame({map.width, map.height});
    std::ostringstream s;
    s << flag << " " << text << ": lies outside the imported map, which spans x from " << lo.x
      << " to " << hi.x << " m and y from " << lo.y << " to " << hi.y << " m in the map frame";
    throw InputError(s.str());
  }
  if (const int o = map.obstacle_at(p); o >= 0)
    throw InputError(flag + " " + text + ": lies inside obstacles[" + std::to_string(o) +
                     "] of the imported map (occupied pixels); give a point in free space");
  return p;
}

void add_import_ros(CLI::App& map_cmd) {
  auto* cmd = map_cmd.add_subcommand(
      "import-ros",
      "Convert a ROS map_server map (YAML + PGM/PNG) to a plumekit-map/2 file in its map frame");
  struct Args {
    std::string yaml;
    std::string out;
    std::string unknown = "occupied";
    RosImportOptions options;
    std::vector<std::string> sources, starts;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("MAP_YAML", a->yaml, "map_server YAML file")->required();
  cmd->add_option("--out,-o", a->out, "plumekit map file to write (new, or one plumekit wrote)")
      ->required();
  const OptionTable<RosImportOptions>& table = ros_import_option_table();
  add_table_flags(cmd, a->options, table, {"ros.simplify_px"});
  bind_field(cmd,
             cmd->add_option("--unknown", a->unknown, "How to treat unknown (unexplored) pixels")
                 ->capture_default_str()
                 ->check(CLI::IsMember({"occupied", "free"})),
             "ros.unknown");
  add_table_flags(cmd, a->options, table, {"ros.min_area_px", "ros.close_gaps_m"});
  bind_field(cmd,
             cmd->add_option("--inlet", a->options.inlets,
                             "Inlet X1,Y1,X2,Y2[,SPEED[,PROFILE]] in the map frame (m; m/s, "
                             "default 1; uniform|parabolic), snapped onto the free space's "
                             "boundary; repeat for more")
                 ->expected(1)
                 ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll),
             "ros.inlets");
  bind_field(cmd,
             cmd->add_option("--outlet", a->options.outlets,
                             "Outlet X1,Y1,X2,Y2 in the map frame (m), snapped likewise; repeat "
                             "for more")
                 ->expected(1)
                 ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll),
             "ros.outlets");
  add_table_flags(cmd, a->options, table, {"ros.snap_px"});
  cmd->add_option("--source", a->sources,
                  "Ground-truth source X,Y in the map frame (m), for `evaluate`; repeat for more")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--start", a->starts,
                  "Robot start X,Y in the map frame (m): `evaluate` starts its runs from these in "
                  "turn instead of random points; repeat for more")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--name", a->options.name, "Map name (default: the YAML file's stem)");
  add_common_flags(cmd);
  cmd->callback([a, cmd] {
    a->options.unknown_is_occupied = a->unknown == "occupied";
    check_output_file(a->out, {a->yaml});
    RosImport in = import_ros_map(a->yaml, a->options);
    for (const std::string& text : a->sources)
      in.map.sources.push_back(imported_point(in.map, text, "--source"));
    for (const std::string& text : a->starts)
      in.map.starts.push_back(imported_point(in.map, text, "--start"));
    in.map.generated_by = "plumekit map import-ros";
    write_output_file(a->out, map_file_text(in.map, a->out));
    ordered_json j = ros_import_json(in, a->yaml, a->out);
    for (auto& w : j["warnings"]) {
      w = with_flag_names(*cmd, w.get<std::string>());
      warn(w.get<std::string>());
    }
    report(j, with_flag_names(*cmd, ros_import_text(in, a->out)));
  });
}

}  // namespace

void add_map_commands(CLI::App& app) {
  auto* map_cmd = app.add_subcommand("map", "Check, draw and import maps");
  map_cmd->require_subcommand(1);
  add_validate(*map_cmd);
  add_render(*map_cmd);
  add_import_ros(*map_cmd);
}

}  // namespace plumekit::cli
