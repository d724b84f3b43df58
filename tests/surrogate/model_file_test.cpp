// plumekit-cnn/1: the architecture's parameter count, and each kind of malformed file refused.
#include "surrogate/model_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"
#include "surrogate/network.hpp"

namespace plumekit::surrogate {
namespace {

const std::string kOdd = std::string(PLUMEKIT_TEST_DATA) + "/surrogate/odd.pkcnn";

TEST(ModelFile, DesignArchitectureHas600130Parameters) {
  EXPECT_EQ(parameter_count(deepcfd_layers(Architecture{})), 600130u);
}

TEST(ModelFile, ReadsTheGoldenFile) {
  const ModelFile m = read_model_file(kOdd);
  EXPECT_EQ(m.architecture.filters, (std::vector<int>{3, 5, 7, 9}));
  EXPECT_EQ(m.architecture.kernel, 3);
  EXPECT_EQ(m.features.rows, 21);
  EXPECT_EQ(m.features.cols, 30);
  EXPECT_EQ(m.features.source_distance_form, "euclidean");
  ASSERT_EQ(m.outputs.size(), 2u);
  EXPECT_EQ(m.outputs[0].name, "mean");
  EXPECT_FLOAT_EQ(m.outputs[0].scale, 2.5f);
  EXPECT_EQ(m.layers.size(), m.weights.size());
}

// A model file taken apart, to be edited and put back together with a correct checksum.
struct Parts {
  std::string prefix;  // magic + version
  nlohmann::json header;
  std::string data;

  explicit Parts(const std::string& bytes) {
    std::uint32_t len;
    std::memcpy(&len, bytes.data() + 12, 4);
    prefix = bytes.substr(0, 12);
    header = nlohmann::json::parse(bytes.substr(16, len));
    const std::size_t offset = (16 + len + 15) / 16 * 16;
    data = bytes.substr(offset, bytes.size() - offset - 32);
  }
  std::string bytes() const {
    const std::string text = header.dump();
    const auto len = static_cast<std::uint32_t>(text.size());
    std::string out = prefix + std::string(reinterpret_cast<const char*>(&len), 4) + text;
    out.resize((out.size() + 15) / 16 * 16, '\0');
    out += data;
    const Sha256Digest d = sha256(out);
    return out + std::string(d.begin(), d.end());
  }
};

void expect_refused(const std::string& bytes, const std::string& fault) {
  try {
    const Network net(parse_model_file(bytes, "bad.pkcnn"));
    ADD_FAILURE() << "accepted a file that should fail with \"" << fault << "\"";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.pkcnn"), std::string::npos) << what;
    EXPECT_NE(what.find(fault), std::string::npos) << what;
  }
}

TEST(ModelFile, RoundTripOfTheTestHelperIsAccepted) {
  EXPECT_NO_THROW(parse_model_file(Parts(read_file(kOdd)).bytes(), "ok.pkcnn"));
}

TEST(ModelFile, RefusesTruncated) {
  const std::string good = read_file(kOdd);
  expect_refused(good.substr(0, good.size() - 100), "truncated");
  expect_refused(good.substr(0, 40), "truncated");
  expect_refused(good.substr(0, 10), "truncated");
  expect_refused(good + "x", "unexpected bytes");
}

TEST(ModelFile, RefusesWrongMagic) {
  std::string bad = read_file(kOdd);
  bad[0] = 'Q';
  expect_refused(bad, "wrong magic");
}

TEST(ModelFile, RefusesUnknownVersion) {
  std::string bad = read_file(kOdd);
  bad[8] = 2;
  expect_refused(bad, "unknown version 2");
}

TEST(ModelFile, RefusesShapeMismatch) {
  Parts p(read_file(kOdd));
  p.header["layers"][4]["weight_shape"][1] = 6;
  expect_refused(p.bytes(), "shape mismatch");

  Parts q(read_file(kOdd));
  q.header["architecture"]["filters"][3] = 8;  // the layer table and tensors still say 9
  expect_refused(q.bytes(), "shape mismatch");

  Parts r(read_file(kOdd));
  r.data.resize(r.data.size() - 4);
  r.header["data_bytes"] = r.data.size();
  expect_refused(r.bytes(), "shape mismatch");
}

TEST(ModelFile, RefusesChecksumMismatch) {
  std::string bad = read_file(kOdd);
  bad[bad.size() - 1000] ^= 0x01;  // one bit in a tensor
  expect_refused(bad, "checksum mismatch");
}

TEST(ModelFile, RefusesNaNWeights) {
  Parts p(read_file(kOdd));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&p.data[4 * 123], &nan, 4);
  expect_refused(p.bytes(), "NaN");
}

// The source channel's two forms: metres, or 1/m (with its floor min_distance, by default half
// the smaller cell side); anything else, or a unit that does not fit the form, is refused.
TEST(ModelFile, ReadsBothSourceChannelForms) {
  const std::string odd = read_file(kOdd);
  Parts inverse(odd);
  nlohmann::json& channel = inverse.header["features"]["channels"][2];
  channel["form"] = "inverse";
  channel["unit"] = "1/m";
  const ModelFile a = parse_model_file(inverse.bytes(), "inverse.pkcnn");
  EXPECT_EQ(a.features.source_distance_form, "inverse");
  // odd.pkcnn: a 21 x 30 grid over 7.5 x 5.25 m, cells of 0.25 x 0.25 m.
  EXPECT_DOUBLE_EQ(a.features.source_min_distance, 0.125);
  channel["min_distance"] = 0.05;
  EXPECT_DOUBLE_EQ(parse_model_file(inverse.bytes(), "inverse.pkcnn").features.source_min_distance,
                   0.05);
  channel["min_distance"] = -1.0;
  expect_refused(inverse.bytes(), "min_distance");
  channel.erase("min_distance");
  channel["unit"] = "m";  // the inverse of a distance is not in metres
  expect_refused(inverse.bytes(), "1/m in the inverse form");
  Parts unknown(odd);
  unknown.header["features"]["channels"][2]["form"] = "log";
  expect_refused(unknown.bytes(), "form \"log\" is unknown");
}

// What the model was trained on: optional ranges and walls, read when present, refused when
// malformed.
TEST(ModelFile, ReadsWhatTheModelWasTrainedOn) {
  const std::string odd = read_file(kOdd);
  EXPECT_FALSE(parse_model_file(odd, "odd.pkcnn").trained_on.map_width);  // none stated
  Parts p(odd);
  p.header["trained_on"] = {
      {"map_width_m", {6, 30}}, {"inlet_speed_m_s", {0.3, 2}}, {"inlet_walls", {"left", "top"}}};
  const TrainingRanges t = parse_model_file(p.bytes(), "ok.pkcnn").trained_on;
  ASSERT_TRUE(t.map_width && t.inlet_speed);
  EXPECT_EQ(t.map_width->lo, 6.0);
  EXPECT_EQ(t.inlet_speed->hi, 2.0);
  EXPECT_FALSE(t.map_height);
  EXPECT_EQ(t.inlet_walls, (std::vector<std::string>{"left", "top"}));
  p.header["trained_on"]["map_width_m"] = {30, 6};
  expect_refused(p.bytes(), "trained_on.map_width_m");
  p.header["trained_on"]["map_width_m"] = {6, 30};
  p.header["trained_on"]["inlet_walls"] = {"ceiling"};
  expect_refused(p.bytes(), "ceiling");
}

}  // namespace
}  // namespace plumekit::surrogate
