// Animations (core/animation.hpp): the animated PNG holds every frame losslessly in APNG's order,
// the MP4 is read back frame by frame before it is moved into place, both carry plumekit's mark,
// and the output rule holds.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <zlib.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/animation.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/output_target.hpp"

namespace plumekit {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "plumekit-animation-test";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

// Frame k: a coloured square moving right, its number in the corner.
cv::Mat frame(int k, cv::Size size = {640, 360}) {
  cv::Mat m(size, CV_8UC3, cv::Scalar(250, 245, 240));
  cv::rectangle(m, cv::Rect(20 + 30 * k, 100, 80, 80), cv::Scalar(30, 60 + 20 * k, 200),
                cv::FILLED);
  cv::putText(m, std::to_string(k), {10, 30}, cv::FONT_HERSHEY_SIMPLEX, 1.0, {0, 0, 0}, 2);
  return m;
}

std::uint32_t be32(const std::string& s, std::size_t at) {
  return (std::uint32_t{static_cast<unsigned char>(s[at])} << 24) |
         (std::uint32_t{static_cast<unsigned char>(s[at + 1])} << 16) |
         (std::uint32_t{static_cast<unsigned char>(s[at + 2])} << 8) |
         static_cast<unsigned char>(s[at + 3]);
}

std::string chunk(const std::string& type, const std::string& data) {
  std::string out;
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<char>((data.size() >> shift) & 0xff));
  out += type + data;
  const std::string typed = type + data;
  const uLong crc =
      crc32(0L, reinterpret_cast<const Bytef*>(typed.data()), static_cast<uInt>(typed.size()));
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<char>((crc >> shift) & 0xff));
  return out;
}

TEST(Animation, AnAnimatedPngHoldsEveryFrameLosslesslyInOrder) {
  const fs::path file = scratch("moving.png");
  AnimationWriter w(file, 5.0, "--animate");
  for (int k = 0; k < 6; ++k)
    w.add(frame(k));
  const AnimationWriter::Written done = w.finish();
  EXPECT_EQ(done.file, file);
  EXPECT_EQ(done.format, "apng");
  EXPECT_EQ(done.frames, 6);
  EXPECT_TRUE(written_by_plumekit(file));
  // The chunks: IHDR, acTL (6 frames, looping), then per frame an fcTL and its data, with one
  // sequence over fcTL and fdAT.
  const std::string bytes = read_file(file);
  std::string ihdr;
  std::vector<std::string> frames;
  std::uint32_t sequence = 0;
  int actl_frames = -1;
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const std::uint32_t length = be32(bytes, at);
    const std::string type = bytes.substr(at + 4, 4), data = bytes.substr(at + 8, length);
    if (type == "IHDR") ihdr = data;
    if (type == "acTL") actl_frames = static_cast<int>(be32(data, 0));
    if (type == "fcTL") {
      EXPECT_EQ(be32(data, 0), sequence++);
      EXPECT_EQ(be32(data, 4), 640u);
      frames.emplace_back();
    }
    if (type == "IDAT") frames.back() += data;
    if (type == "fdAT") {
      EXPECT_EQ(be32(data, 0), sequence++);
      frames.back() += data.substr(4);
    }
    at += 12 + length;
  }
  EXPECT_EQ(actl_frames, 6);
  ASSERT_EQ(frames.size(), 6u);
  for (int k = 0; k < 6; ++k) {
    const std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) +
                            chunk("IDAT", frames[k]) + chunk("IEND", "");
    const cv::Mat decoded =
        cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_COLOR);
    ASSERT_FALSE(decoded.empty()) << k;
    EXPECT_EQ(cv::norm(decoded, frame(k), cv::NORM_INF), 0.0) << "frame " << k;
  }
  // Its own earlier output is replaced.
  AnimationWriter again(file, 5.0, "--animate");
  again.add(frame(0));
  EXPECT_EQ(again.finish().frames, 1);
  fs::remove(file);
}

TEST(Animation, AVideoIsReadBackAndMarked) {
  const fs::path module = fs::path(PLUMEKIT_EXE).parent_path() / "libplumekit_video.so";
  ASSERT_TRUE(fs::exists(module)) << module;
  ::setenv("PLUMEKIT_VIDEO_MODULE", module.c_str(), 1);
  EXPECT_EQ(find_video_module().error, "");
  const fs::path file = scratch("moving.mp4");
  AnimationWriter w(file, 10.0, "--animate");
  for (int k = 0; k < 12; ++k)
    w.add(frame(k % 6));
  const AnimationWriter::Written done = w.finish();
  EXPECT_EQ(done.format, "mp4");
  EXPECT_EQ(done.frames, 12);
  EXPECT_EQ(done.note, "");
  const std::string bytes = read_file(file);
  EXPECT_EQ(bytes.substr(4, 4), "ftyp");
  EXPECT_TRUE(written_by_plumekit(file));
  // A video someone else made (the same bytes without the mark) is not plumekit's.
  const std::string mark = plumekit_mark();
  std::ofstream(file, std::ios::binary | std::ios::trunc)
      << bytes.substr(0, bytes.size() - 8 - mark.size());
  EXPECT_FALSE(written_by_plumekit(file));
  EXPECT_THROW(AnimationWriter(file, 10.0, "--animate"), InputError);
  fs::remove(file);
}

TEST(Animation, RefusesOtherFormatsAndFilesItDidNotWrite) {
  try {
    AnimationWriter w(scratch("run.gif"), 10.0, "--animate");
    ADD_FAILURE() << "a GIF was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--animate"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(".mp4"), std::string::npos) << e.what();
  }
  const fs::path mine = scratch("notes.png");
  std::ofstream(mine) << "a user's file";
  EXPECT_THROW(AnimationWriter(mine, 10.0, "--animate"), InputError);
  EXPECT_EQ(read_file(mine), "a user's file");
  EXPECT_THROW(AnimationWriter(scratch("x.png"), 0.0, "--fps"), InputError);
  fs::remove(mine);
}

}  // namespace
}  // namespace plumekit
