// Range checks (core/option_check.hpp), the memory limit and its guard
// (core/memory_limit.hpp), and the guards of rasterization, map pictures and
// the bounded grid check of huge arenas.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/memory_limit.hpp"
#include "core/option_check.hpp"
#include "map/map_render.hpp"
#include "map/rasterize.hpp"
#include "map/ros_import.hpp"

namespace plumekit {
namespace {

// Sets the process's memory limit for one test and restores the default after.
class MemoryLimitScope {
 public:
  explicit MemoryLimitScope(double bytes) { set_memory_limit(bytes); }
  ~MemoryLimitScope() { set_memory_limit(default_memory_limit()); }
};

template <class F>
OptionError option_error(F&& f) {
  try {
    f();
  } catch (const OptionError& e) {
    return e;
  }
  ADD_FAILURE() << "no OptionError";
  return OptionError("", "");
}

TEST(OptionCheck, CompactPrintsHugeAndOddValuesShort) {
  EXPECT_EQ(compact(0.05), "0.05");
  EXPECT_EQ(compact(DBL_MAX), "1.798e+308");
  EXPECT_EQ(compact(NAN), "nan");
  EXPECT_EQ(compact(-INFINITY), "-inf");
}

TEST(OptionCheck, RangeErrorNamesFieldRangeAndValue) {
  const OptionError e = option_error([] { check_positive("flow.cell", NAN, 10.0, "m", "x"); });
  EXPECT_EQ(e.field(), "flow.cell");
  EXPECT_NE(e.message().find("more than 0 and at most 10 m"), std::string::npos) << e.message();
  EXPECT_NE(e.message().find("got nan"), std::string::npos) << e.message();
  EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos);
  const OptionError huge = option_error([] { check_positive("flow.nu", DBL_MAX, 10.0, "m^2/s"); });
  EXPECT_LT(huge.message().size(), 100u) << huge.message();
  EXPECT_NO_THROW(check_non_negative("ste.world.noise", 0.0, 1e9, ""));
  EXPECT_THROW(check_non_negative("ste.world.noise", -1e-9, 1e9, ""), OptionError);
  EXPECT_THROW(check_count("n", 0, 1, 10), OptionError);
}

TEST(OptionCheck, UnknownNameListsTheKnownOnes) {
  const OptionError e = option_error([] {
    check_name("maps.families", "U", {"rectangle", "l-shape", "u-shape"});
  });
  EXPECT_EQ(e.field(), "maps.families");
  EXPECT_NE(e.message().find("'U'"), std::string::npos);
  EXPECT_NE(e.message().find("rectangle, l-shape or u-shape"), std::string::npos) << e.message();
}

TEST(MemoryLimit, ParsesSizes) {
  EXPECT_DOUBLE_EQ(parse_memory_size("4G"), 4.0 * 1024 * 1024 * 1024);
  EXPECT_DOUBLE_EQ(parse_memory_size("512M"), 512.0 * 1024 * 1024);
  EXPECT_DOUBLE_EQ(parse_memory_size("2gib"), 2.0 * 1024 * 1024 * 1024);
  EXPECT_DOUBLE_EQ(parse_memory_size("1e9"), 1e9);
  for (const char* bad : {"", "G", "4X", "-1G", "nan", "0", "inf"}) {
    const OptionError e = option_error([&] { parse_memory_size(bad); });
    EXPECT_EQ(e.field(), "memory.limit") << bad;
  }
  EXPECT_THROW(set_memory_limit(NAN), OptionError);
  EXPECT_THROW(set_memory_limit(100.0), OptionError);  // under 1 MiB
}

TEST(MemoryLimit, DefaultIsHalfThePhysicalMemory) {
  const double physical = physical_memory_bytes();
  ASSERT_GT(physical, 0.0);
  if (!std::getenv("PLUMEKIT_MAX_MEMORY")) {
    EXPECT_DOUBLE_EQ(default_memory_limit(), physical / 2);
  }
  EXPECT_EQ(suggest_limit(14.2 * 1024 * 1024 * 1024), "15G");
  EXPECT_EQ(suggest_limit(700.5 * 1024 * 1024), "701M");
  EXPECT_EQ(format_bytes(88.0 * 1024 * 1024), "88 MiB");
}

TEST(MemoryLimit, CheckNamesWhatTheEstimateTheLimitAndTheFix) {
  const MemoryLimitScope scope(parse_memory_size("1G"));
  EXPECT_NO_THROW(check_memory(1e8, "x", "y"));
  try {
    check_memory(3.5 * 1024 * 1024 * 1024, "the flow solve",
                 "use a larger flow.cell (0.12 m fits)");
    FAIL() << "no MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("the flow solve needs about 3.5 GiB"), std::string::npos) << m;
    EXPECT_NE(m.find("limit of 1.0 GiB"), std::string::npos) << m;
    EXPECT_NE(m.find("flow.cell (0.12 m fits)"), std::string::npos) << m;
    EXPECT_NE(m.find("raise the memory limit to at least 4G"), std::string::npos) << m;
    EXPECT_DOUBLE_EQ(e.limit_bytes(), 1024.0 * 1024 * 1024);
  }
}

TEST(MemoryLimit, RasterizationIsRefusedAboveTheLimit) {
  const MemoryLimitScope scope(parse_memory_size("16M"));
  const Map map = default_arena(1000.0, 1000.0);
  EXPECT_THROW(rasterize_occupancy(map, GridShape::with_cell(1000.0, 1000.0, 0.05)),
               MemoryLimitError);
}

TEST(MapGridCheck, SmallArenaIsCheckedAtTheRequestedCell) {
  Map map = default_arena(10.0, 4.0);
  map.obstacles.push_back({{4.0, 0.0}, {5.0, 0.0}, {5.0, 4.0}, {4.0, 4.0}});  // a wall across
  const MapGridCheck c = map_grid_check(map);
  EXPECT_FALSE(c.coarsened);
  EXPECT_DOUBLE_EQ(c.cell, 0.05);
  EXPECT_NEAR(c.free_fraction, 0.9, 1e-9);
  EXPECT_FALSE(c.inlet_reaches_outlet);
  EXPECT_TRUE(map_grid_check(default_arena()).inlet_reaches_outlet);
}

TEST(MapGridCheck, HugeArenaIsCheckedOnABoundedGrid) {
  for (double side : {1000.0, 1e6}) {
    Map map = default_arena(side, side);
    map.obstacles.push_back(
        {{0.4 * side, 0.0}, {0.5 * side, 0.0}, {0.5 * side, 0.5 * side}, {0.4 * side, 0.5 * side}});
    const MapGridCheck c = map_grid_check(map);
    EXPECT_TRUE(c.coarsened);
    EXPECT_LE(static_cast<double>(c.shape.size()), kMaxCheckCells);
    EXPECT_GE(c.cell, side / 2001);
    EXPECT_NEAR(c.free_fraction, 0.95, 1e-3);
    EXPECT_TRUE(c.inlet_reaches_outlet);
  }
}

TEST(MapRender, PixelsPerMetreIsRangeChecked) {
  const Map map = default_arena();
  for (double bad : {double(NAN), 0.0, -5.0, 1e4, double(INFINITY)}) {
    const OptionError e = option_error([&] { MapCanvas canvas(map, bad); });
    EXPECT_EQ(e.field(), "render.px_per_m") << bad;
  }
  EXPECT_NO_THROW(MapCanvas(map, 100.0));
}

TEST(MapRender, HugeArenaPictureIsRefusedWithTheScaleThatFits) {
  const Map map = default_arena(1000.0, 1000.0);
  const OptionError e = option_error([&] { MapCanvas canvas(map, 100.0); });
  EXPECT_EQ(e.field(), "render.px_per_m");
  EXPECT_NE(e.message().find("render.px_per_m (29.83 fits)"), std::string::npos) << e.message();
  const MemoryLimitScope scope(parse_memory_size("64M"));
  try {
    MapCanvas canvas(default_arena(100.0, 100.0), 100.0);
    FAIL() << "no MemoryLimitError";
  } catch (const MemoryLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("render.px_per_m"), std::string::npos) << e.what();
  }
}

TEST(RosImport, ImageTooBigForTheLimitIsRefusedFromItsHeader) {
  // Headers that claim 100000 x 100000 pixels (240 GB to import) and carry no
  // pixels: refused before any pixel is read, naming the image's size.
  const auto dir =
      std::filesystem::temp_directory_path() / ("plumekit_ros_limit_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string png_header("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\x01\x86\xa0\0\x01\x86\xa0", 24);
  for (const auto& [name, header] :
       {std::pair<std::string, std::string>{"big.pgm", "P5\n# a comment\n100000 100000\n255\n"},
        {"big.png", png_header}}) {
    std::ofstream(dir / name, std::ios::binary) << header;
    std::ofstream(dir / "big.yaml") << "image: " << name
                                    << "\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
                                       "occupied_thresh: 0.65\nfree_thresh: 0.196\n";
    try {
      import_ros_map(dir / "big.yaml", {});
      ADD_FAILURE() << name << ": no MemoryLimitError";
    } catch (const MemoryLimitError& e) {
      EXPECT_NE(std::string(e.what()).find("importing the 1e+05 x 1e+05 px image"),
                std::string::npos)
          << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace plumekit
