#include "core/image_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace fs = std::filesystem;
using plumekit::encode_png;
using plumekit::read_gray_image;

namespace {

// A picture with smooth parts, edges and noise, like the rendered maps.
cv::Mat picture(int type) {
  cv::Mat img(61, 83, type, cv::Scalar::all(30));
  cv::RNG rng(7);
  cv::Mat noise(img.size(), type);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  noise(cv::Rect(40, 0, 43, 61)).copyTo(img(cv::Rect(40, 0, 43, 61)));
  cv::circle(img, {20, 30}, 15, cv::Scalar(200, 90, 10, 128), -1, cv::LINE_AA);
  return img;
}

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / "plumekit_image_io_test";
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(ImageIo, PngBytesMatchOpenCv) {
  for (int type : {CV_8UC1, CV_8UC3, CV_8UC4}) {
    const cv::Mat img = picture(type);
    std::vector<uchar> expected;
    ASSERT_TRUE(cv::imencode(".png", img, expected));
    const std::string ours = encode_png(img);
    EXPECT_EQ(ours, std::string(expected.begin(), expected.end())) << "type " << type;
    // And it decodes to the same pixels.
    const cv::Mat back =
        cv::imdecode(std::vector<uchar>(ours.begin(), ours.end()), cv::IMREAD_UNCHANGED);
    EXPECT_EQ(cv::norm(back, img, cv::NORM_INF), 0.0);
  }
}

TEST(ImageIo, RefusesUnsupportedImages) {
  EXPECT_THROW(encode_png(cv::Mat()), std::runtime_error);
  EXPECT_THROW(encode_png(cv::Mat(4, 4, CV_32FC1, cv::Scalar(1))), std::runtime_error);
  EXPECT_THROW(encode_png(cv::Mat(4, 4, CV_8UC2, cv::Scalar(1))), std::runtime_error);
}

TEST(ImageIo, ReadsLikeImreadGrayscale) {
  const fs::path dir = temp_dir();
  const cv::Mat gray = picture(CV_8UC1), colour = picture(CV_8UC3), rgba = picture(CV_8UC4);
  cv::Mat wide;
  gray.convertTo(wide, CV_16U, 257.0);
  const std::pair<const char*, const cv::Mat*> cases[] = {{"g.pgm", &gray},   {"g.png", &gray},
                                                          {"c.png", &colour}, {"a.png", &rgba},
                                                          {"w.png", &wide},   {"w.pgm", &wide}};
  for (const auto& [name, img] : cases) {
    const fs::path path = dir / name;
    ASSERT_TRUE(cv::imwrite(path.string(), *img));
    const cv::Mat expected = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat ours = read_gray_image(path);
    ASSERT_EQ(ours.size(), expected.size()) << name;
    ASSERT_EQ(ours.type(), CV_8UC1) << name;
    EXPECT_LE(cv::norm(ours, expected, cv::NORM_INF), 1.0) << name;
  }
}

TEST(ImageIo, ReadsAsciiPgmWithCommentsAndSmallMaxval) {
  const fs::path path = temp_dir() / "ascii.pgm";
  std::ofstream(path) << "P2\n# a comment\n3 2\n# another\n15\n0 15 7\n8 1 15\n";
  const cv::Mat img = read_gray_image(path);
  ASSERT_EQ(img.rows, 2);
  ASSERT_EQ(img.cols, 3);
  EXPECT_EQ(img.at<uchar>(0, 0), 0);
  EXPECT_EQ(img.at<uchar>(0, 1), 255);
  EXPECT_EQ(img.at<uchar>(0, 2), (7 * 255 + 7) / 15);
  EXPECT_EQ(img.at<uchar>(1, 2), 255);
}

TEST(ImageIo, BadFilesGiveAnEmptyImage) {
  const fs::path dir = temp_dir();
  EXPECT_TRUE(read_gray_image(dir / "missing.png").empty());
  std::ofstream(dir / "text.png") << "not an image at all";
  EXPECT_TRUE(read_gray_image(dir / "text.png").empty());
  std::ofstream(dir / "short.pgm", std::ios::binary) << "P5\n10 10\n255\n\x01\x02";
  EXPECT_TRUE(read_gray_image(dir / "short.pgm").empty());
  std::string png = encode_png(picture(CV_8UC1));
  png.resize(png.size() / 2);
  std::ofstream(dir / "cut.png", std::ios::binary) << png;
  EXPECT_TRUE(read_gray_image(dir / "cut.png").empty());
}
