#pragma once
// Narrow gaps: two features of a map (obstacles, or an obstacle and an arena
// wall) that do not touch but are less than one cell apart. Whether such a gap
// leaves a channel of free cells on the grid would depend on how the cells
// happen to fall, so it is closed: every free cell whose centre p lies in the
// gap region, dist(p, A) + dist(p, B) < cell, is made solid. Between two
// parallel edges d apart that region is the strip between them (plus small
// caps at its ends), so the gap's cells are all closed, whatever the
// alignment. Gaps of exactly one cell or wider are left as the rasterization
// makes them.
//
// The search runs on a grid of buckets (one cell wide) holding the obstacles'
// edges, so it takes time in proportion to the edges and the cells near them,
// not to the square of the obstacle count (docs/design/flow-solver.md, "Narrow gaps").
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "map/map.hpp"

namespace plumekit::cfd {

struct GapReport {
  int a = -1;                // obstacle index
  int b = -1;                // obstacle index, or -1 when the other side is `wall`
  std::optional<Side> wall;  // the arena wall, when b is -1
  double width = 0.0;        // m, the shortest distance between the two
  Vec2 at;                   // arena frame: midway between the closest points
  int cells_closed = 0;      // free cells this gap's closing made solid
};

// The relative margin under which a gap counts as narrower than a cell: a gap
// of exactly one cell, up to round-off in the coordinates, is not narrow; and
// features less than this share of a cell apart touch (no gap).
inline constexpr double kGapTolerance = 1e-9;

// The gaps narrower than the grid's larger cell side, narrowest first (ties
// by obstacle indices). Nothing is changed.
std::vector<GapReport> find_narrow_gaps(const Map& map, const GridShape& shape);

// Finds the narrow gaps and makes solid the free cells of `solid` (row-major,
// 1 solid, as rasterize_occupancy gives it) that lie in their gap regions.
// Returns the gaps, narrowest first; `closed_by`, when given, receives for
// each cell the index (in the returned list) of the gap that closed it, or -1.
std::vector<GapReport> close_narrow_gaps(const Map& map, const GridShape& shape,
                                         std::vector<std::uint8_t>& solid,
                                         std::vector<int>* closed_by = nullptr);

// The brute-force reference: every pair of obstacles (and each obstacle with
// each wall), O(P^2 V^2). For tests.
std::vector<GapReport> find_narrow_gaps_brute_force(const Map& map, const GridShape& shape);

// "obstacles[3] and obstacles[7], 0.012 m apart at (1.2, 3.45)": the position
// in the map frame (map.to_frame).
std::string describe_gap(const Map& map, const GapReport& gap);

// The largest cell (a value with at most two significant digits) whose grid on
// this arena has no gap narrower than a cell, given the narrowest gap's width:
// both cell sides of GridShape::with_cell come out at most `narrowest`.
double cell_keeping_gaps_open(const Map& map, double narrowest);

// What a flow reports of the gaps its grid closed, for people: positions in
// the map frame.
struct ClosedGap {
  std::string between;  // "obstacles[3] and the left wall"
  double width = 0.0;   // m
  Vec2 at;              // map frame
};
struct ClosedGaps {
  int count = 0;
  std::vector<ClosedGap> narrowest;  // the first kReportedGaps, narrowest first
  double open_cell = 0.0;            // m, cell_keeping_gaps_open of the narrowest (0: none)
};
inline constexpr std::size_t kReportedGaps = 5;
ClosedGaps summarize_gaps(const Map& map, const std::vector<GapReport>& gaps);
// "closed 3 gaps narrower than the 0.05 m cell (open in the map): obstacles[3]
// and obstacles[7], 0.012 m apart at (1.2, 3.45); ...; a cell of 0.012 m keeps
// them open". Empty when none was closed.
std::string closed_gaps_text(const ClosedGaps& gaps, double cell);

// A map-frame coordinate to the millimetre, without trailing zeros: "103.006", "-19.6"
// (compact's significant digits would drop the millimetres far from the origin). The gap and
// thin-wall reports both place what they name with it.
std::string millimetre_coordinate(double v);

}  // namespace plumekit::cfd
