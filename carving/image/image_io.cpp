#include "carving/image/image_io.hpp"

#include <fmt/format.h>

#include <opencv2/imgcodecs.hpp>
#include <string>

#include "core/errors.hpp"

namespace suite::carving {

cv::Mat read_image(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("cannot read image '{}': no such file", path.string()));
  cv::Mat image;
  std::string detail;
  try {
    image = cv::imread(path.string(), cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    detail = e.err;
  }
  if (image.empty())
    throw InputError(
        fmt::format("cannot read image '{}': empty, corrupt or not a format OpenCV decodes (PNG, JPEG, "
                    "TIFF, BMP){}{}",
                    path.string(), detail.empty() ? "" : "; OpenCV: ", detail));
  return image;
}

cv::Mat mask_image(const Mask& mask) {
  cv::Mat image(mask.height(), mask.width(), CV_8UC1);
  for (int y = 0; y < mask.height(); ++y) {
    auto* row = image.ptr<std::uint8_t>(y);
    for (int x = 0; x < mask.width(); ++x) row[x] = mask.at(x, y) ? 255 : 0;
  }
  return image;
}

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
  if (image.empty()) throw InputError(fmt::format("cannot write '{}': the image is empty", path.string()));
  bool ok = false;
  std::string detail;
  try {
    ok = cv::imwrite(path.string(), image);
  } catch (const cv::Exception& e) {
    detail = e.err;
  }
  if (!ok)
    throw InputError(
        fmt::format("cannot write image '{}': check that the folder exists and is writable and that the "
                    "extension is one OpenCV writes (.png){}{}",
                    path.string(), detail.empty() ? "" : "; OpenCV: ", detail));
}

void write_mask_png(const std::filesystem::path& path, const Mask& mask) {
  write_png(path, mask_image(mask));
}

Mask mask_from_image(const cv::Mat& gray) {
  if (gray.empty() || gray.type() != CV_8UC1)
    throw InputError(
        fmt::format("mask_from_image: the image is {} x {} of OpenCV type {}; give a non-empty 8-bit "
                    "single-channel image",
                    gray.cols, gray.rows, gray.type()));
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(gray.cols) * gray.rows);
  for (int y = 0; y < gray.rows; ++y) {
    const auto* row = gray.ptr<std::uint8_t>(y);
    for (int x = 0; x < gray.cols; ++x) pixels[static_cast<std::size_t>(y) * gray.cols + x] = row[x] != 0;
  }
  return Mask(gray.cols, gray.rows, std::move(pixels));
}

}  // namespace suite::carving
