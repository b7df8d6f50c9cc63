#pragma once
// Reading and writing images and masks; every failure is an InputError naming the file. PNGs
// are read and written with libpng (png_codec.hpp); the other formats are read with OpenCV's
// imgcodecs from a plugin loaded on the first such image (imgcodecs_plugin.hpp).
#include <filesystem>
#include <opencv2/core.hpp>

#include "carving/image/mask.hpp"

namespace suite::carving {

// Reads a colour image as 8-bit BGR, as cv::imread(IMREAD_COLOR) does; InputError naming the
// file when it is missing, unreadable or empty.
cv::Mat read_image(const std::filesystem::path& path);

// Writes an 8-bit grey or BGR image, or a mask (0 / 255), as PNG to `path`. InputError naming
// the path when it cannot be written.
void write_png(const std::filesystem::path& path, const cv::Mat& image);
void write_mask_png(const std::filesystem::path& path, const Mask& mask);

// A mask as an 8-bit image, 255 = seed, and back (non-zero = seed, e.g. a mask PNG read with
// cv::IMREAD_GRAYSCALE).
cv::Mat mask_image(const Mask& mask);
Mask mask_from_image(const cv::Mat& gray);

}  // namespace suite::carving
