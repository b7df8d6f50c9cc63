// Tests of seedcarve's image reading and writing (carving/image/image_io.hpp): PNGs, read with
// libpng, give exactly the pixels cv::imread(IMREAD_COLOR) gives, whatever their colour type and
// depth; the other formats, read through the imgcodecs plugin, too; written PNGs read back
// exactly; damaged files are InputErrors naming the file.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "carving/image/image_io.hpp"
#include "core/errors.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::carving {
namespace {

// A 8-bit (or 16-bit) image with every kind of pixel: smooth gradients, a seeded noise field and
// saturated corners, so that a wrong channel order, a dropped byte or a wrong 16 -> 8 bit rule
// changes some pixel.
cv::Mat test_pattern(int type) {
  cv::Mat image(37, 53, type);
  cv::RNG rng(20261127);
  rng.fill(image, cv::RNG::UNIFORM, cv::Scalar::all(0), cv::Scalar::all(CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256));
  image(cv::Rect(0, 0, 4, 4)).setTo(cv::Scalar::all(0));
  image(cv::Rect(49, 33, 4, 4)).setTo(cv::Scalar::all(CV_MAT_DEPTH(type) == CV_16U ? 65535 : 255));
  return image;
}

double max_difference(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return -1;
  return cv::norm(a, b, cv::NORM_INF);
}

TEST(ImageIo, PngsReadAsOpenCvReadsThem) {
  const auto dir = testing::scratch_dir();
  const std::vector<std::pair<std::string, int>> kinds = {
      {"bgr8", CV_8UC3}, {"grey8", CV_8UC1}, {"bgra8", CV_8UC4}, {"bgr16", CV_16UC3}, {"grey16", CV_16UC1}};
  for (const auto& [name, type] : kinds) {
    const auto path = dir / (name + ".png");
    ASSERT_TRUE(cv::imwrite(path.string(), test_pattern(type)));
    const cv::Mat expected = cv::imread(path.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(expected.empty()) << name;
    EXPECT_EQ(max_difference(read_image(path), expected), 0.0) << name;
  }
}

TEST(ImageIo, OtherFormatsReadThroughThePlugin) {
  const auto dir = testing::scratch_dir();
  const cv::Mat pattern = test_pattern(CV_8UC3);
  for (const std::string name : {"view.jpg", "view.bmp", "view.tif", "view.ppm"}) {
    const auto path = dir / name;
    ASSERT_TRUE(cv::imwrite(path.string(), pattern)) << name;
    const cv::Mat expected = cv::imread(path.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(expected.empty()) << name;
    EXPECT_EQ(max_difference(read_image(path), expected), 0.0) << name;
  }
  // A grey BMP comes back as three equal channels, as from cv::imread.
  const auto grey = dir / "grey.bmp";
  ASSERT_TRUE(cv::imwrite(grey.string(), test_pattern(CV_8UC1)));
  EXPECT_EQ(max_difference(read_image(grey), cv::imread(grey.string(), cv::IMREAD_COLOR)), 0.0);
}

TEST(ImageIo, WrittenPngsReadBackExactly) {
  const auto dir = testing::scratch_dir();
  for (const int type : {CV_8UC3, CV_8UC1}) {
    const cv::Mat pattern = test_pattern(type);
    const auto path = dir / ("written" + std::to_string(type) + ".png");
    write_png(path, pattern);
    EXPECT_EQ(max_difference(cv::imread(path.string(), cv::IMREAD_UNCHANGED), pattern), 0.0) << type;
    cv::Mat colour = pattern;
    if (type == CV_8UC1) cv::cvtColor(pattern, colour, cv::COLOR_GRAY2BGR);
    EXPECT_EQ(max_difference(read_image(path), colour), 0.0) << type;
  }
  // What PNG cannot hold here is refused by name, before anything is written.
  const auto wide = dir / "float.png";
  EXPECT_NE(
      testing::input_error_of([&] { write_png(wide, cv::Mat(4, 4, CV_32FC1, cv::Scalar(0.5))); }).find(wide.string()),
      std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(wide));
}

TEST(ImageIo, DamagedPngsNameTheFile) {
  const auto dir = testing::scratch_dir();
  const auto good = dir / "good.png";
  write_png(good, test_pattern(CV_8UC3));
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  // Cut in the middle of the pixel data; and the pixel data scrambled (the checksum fails).
  const auto cut = dir / "cut.png";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::string scrambled = bytes;
  for (std::size_t i = bytes.size() / 2; i < bytes.size() / 2 + 64; ++i)
    scrambled[i] = static_cast<char>(~scrambled[i]);
  const auto bad = dir / "scrambled.png";
  std::ofstream(bad, std::ios::binary) << scrambled;
  for (const auto& path : {cut, bad}) {
    const std::string message = testing::input_error_of([&] { read_image(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("PNG"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace suite::carving
