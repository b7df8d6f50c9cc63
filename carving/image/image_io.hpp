#pragma once
// Reading and writing images and masks with OpenCV (imgcodecs); every failure is an InputError
// naming the file.
#include <filesystem>
#include <opencv2/core.hpp>

#include "carving/image/mask.hpp"

namespace suite::carving {

// Reads a colour image with cv::imread (BGR); InputError naming the file when it is missing,
// unreadable or empty.
cv::Mat read_image(const std::filesystem::path& path);

// Writes an image (any type cv::imwrite accepts; PNG for exact pixels) or a mask (0 / 255) to
// `path`. InputError naming the path when OpenCV cannot write it.
void write_png(const std::filesystem::path& path, const cv::Mat& image);
void write_mask_png(const std::filesystem::path& path, const Mask& mask);

// A mask as an 8-bit image, 255 = seed, and back (non-zero = seed, e.g. a mask PNG read with
// cv::IMREAD_GRAYSCALE).
cv::Mat mask_image(const Mask& mask);
Mask mask_from_image(const cv::Mat& gray);

}  // namespace suite::carving
