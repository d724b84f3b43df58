// Reading back what `plumekit flow` wrote (cfd/wind_file.hpp): the same wind,
// bit for bit, and a refusal naming the file and field for every fault.
#include "cfd/wind_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "cfd/flow_output.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/npy.hpp"
#include "core/sha256.hpp"
#include "map/map_json.hpp"

namespace plumekit::cfd {
namespace {

namespace fs = std::filesystem;
const fs::path kMaps = fs::path(PLUMEKIT_DATA_DIR) / "maps";

class WindFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("plumekit-wind-file-" +
           std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
    map = read_map(kMaps / "cluttered-2.json");
    FlowOptions options;
    options.cell = 0.2;
    flow = solve(map, options);
    write_flow(dir, map, flow, options);
  }
  void TearDown() override { fs::remove_all(dir); }

  // Refusal of the wind in `dir` for `m`, with the message's file and words.
  void expect_refused(const Map& m, const std::string& file, const std::string& words) const {
    try {
      read_wind(dir, m);
      ADD_FAILURE() << "read_wind accepted it; expected " << words;
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find((dir / file).string()), std::string::npos) << msg;
      EXPECT_NE(msg.find(words), std::string::npos) << msg;
    }
  }
  nlohmann::ordered_json wind_json() const {
    return nlohmann::ordered_json::parse(read_file(dir / "wind.json"));
  }
  void write_wind_json(const nlohmann::ordered_json& j) const {
    write_file_atomic(dir / "wind.json", j.dump(2));
  }

  fs::path dir;
  Map map;
  FlowResult flow;
};

TEST_F(WindFile, ReadsBackTheSolvedWindBitForBit) {
  const WindField w = read_wind(dir, map);
  EXPECT_EQ(w.shape().nx, flow.wind.shape().nx);
  EXPECT_EQ(w.shape().ny, flow.wind.shape().ny);
  EXPECT_EQ(w.face_u(), flow.wind.face_u());
  EXPECT_EQ(w.face_v(), flow.wind.face_v());
  EXPECT_EQ(w.solid_cells(), flow.wind.solid_cells());
  EXPECT_EQ(w.u(), flow.wind.u());
  const Vec2 a = w.at({3.3, 1.7}), b = flow.wind.at({3.3, 1.7});
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
}

TEST_F(WindFile, TheSameMapFromAnotherFileIsAccepted) {
  // The identity is the map's content, not its file's bytes or path.
  write_map(map, dir / "copy.json");
  EXPECT_NO_THROW(read_wind(dir, read_map(dir / "copy.json")));
  EXPECT_EQ(map_identity(map), map_identity(read_map(dir / "copy.json")));
}

TEST_F(WindFile, RefusesAnotherMapOrAnEditedOne) {
  expect_refused(read_map(kMaps / "cluttered-1.json"), "wind.json", "map_sha256");
  Map moved = map;
  moved.obstacles[0][0].x += 0.01;
  expect_refused(moved, "wind.json", "solved for another map");
}

TEST_F(WindFile, RefusesADamagedArray) {
  std::string bytes = read_file(dir / "face_v.npy");
  bytes[bytes.size() - 3] ^= 0x10;  // one bit of one velocity
  write_file_atomic(dir / "face_v.npy", bytes);
  expect_refused(map, "face_v.npy", "does not match its SHA-256");
}

// u.npy and v.npy are not what read_wind reads, but wind.json lists their
// SHA-256 too: a folder whose listed files do not match is refused, naming the file.
TEST_F(WindFile, RefusesADamagedCellVelocityArray) {
  for (const char* name : {"u.npy", "v.npy"}) {
    const std::string good = read_file(dir / name);
    std::string bytes = good;
    bytes[bytes.size() - 2] ^= 0x01;
    write_file_atomic(dir / name, bytes);
    expect_refused(
        map, name,
        "does not match its SHA-256 in wind.json (arrays_sha256." + std::string(name) + ")");
    fs::remove(dir / name);
    expect_refused(map, name, "missing");
    write_file_atomic(dir / name, good);
  }
  EXPECT_NO_THROW(read_wind(dir, map));
}

TEST_F(WindFile, RefusesAMissingArray) {
  fs::remove(dir / "solid.npy");
  expect_refused(map, "solid.npy", "missing");
}

TEST_F(WindFile, RefusesAWindJsonFromBeforeTheChecksums) {
  nlohmann::ordered_json j = wind_json();
  j.erase("arrays_sha256");
  write_wind_json(j);
  expect_refused(map, "wind.json", "older plumekit");
}

TEST_F(WindFile, RefusesAGridThatIsNotTheMaps) {
  nlohmann::ordered_json j = wind_json();
  j["grid"]["nx"] = j["grid"]["nx"].get<int>() + 1;
  write_wind_json(j);
  expect_refused(map, "wind.json", "grid.dx");
}

TEST_F(WindFile, RefusesANonFiniteVelocityEvenWithAMatchingChecksum) {
  std::vector<double> u = flow.wind.face_u();
  u[u.size() / 2] = std::numeric_limits<double>::quiet_NaN();
  const std::size_t nx = flow.wind.shape().nx, ny = flow.wind.shape().ny;
  const std::string bytes = npy_float64(u, {ny, nx + 1});
  write_file_atomic(dir / "face_u.npy", bytes);
  nlohmann::ordered_json j = wind_json();
  j["arrays_sha256"]["face_u.npy"] = sha256_hex(bytes);
  write_wind_json(j);
  expect_refused(map, "face_u.npy", "not finite");
}

// An .npy header whose shape is huge (found by fuzz_wind_file): refused as
// damaged input, not std::out_of_range or a wrapped size (exit 1).
TEST_F(WindFile, RefusesAnArrayWithAHugeShapeEvenWithAMatchingChecksum) {
  for (const std::string shape :
       {"(99999999999999999999999, 7)", "(4294967296, 4294967297)", "(2305843009213693952, 1)"}) {
    std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': " + shape + ", }";
    dict.append(64 - (10 + dict.size() + 1) % 64, ' ');
    dict += '\n';
    std::string bytes = std::string("\x93NUMPY\x01\x00", 8);
    bytes += static_cast<char>(dict.size() & 0xff);
    bytes += static_cast<char>(dict.size() >> 8);
    bytes += dict;
    write_file_atomic(dir / "face_u.npy", bytes);
    nlohmann::ordered_json j = wind_json();
    j["arrays_sha256"]["face_u.npy"] = sha256_hex(bytes);
    write_wind_json(j);
    expect_refused(map, "face_u.npy",
                   shape == "(99999999999999999999999, 7)" ? "a dimension of the shape is too large"
                   : shape == "(4294967296, 4294967297)"   ? "more values than memory can"
                                                           : "data size does not match the shape");
  }
}

TEST_F(WindFile, RefusesAFolderWithoutAWind) {
  fs::remove(dir / "wind.json");
  expect_refused(map, "wind.json", "plumekit flow");
  write_file_atomic(dir / "wind.json", "{ not json");
  expect_refused(map, "wind.json", "not valid JSON");
}

}  // namespace
}  // namespace plumekit::cfd
