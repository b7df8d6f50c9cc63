#pragma once
// PNG reading and writing with libpng: the seed images' usual format, decoded without OpenCV's
// imgcodecs, whose 140 shared libraries (GDAL, DICOM, HEIF...) took a process two thirds of
// its start-up (image_io.hpp reads the other formats through it, on demand).
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>

namespace suite::carving {

// A PNG as 8-bit BGR, converted as cv::imread(path, IMREAD_COLOR) converts it (16-bit samples
// keep their high byte, grey and palette images are expanded, alpha is dropped); nothing when the
// file does not start with PNG's signature; InputError naming the file when it cannot be opened or
// is a corrupt or truncated PNG.
std::optional<cv::Mat> read_png_bgr(const std::filesystem::path& path);

// An 8-bit grey or BGR image as PNG; zlib `compression_level` 0-9 (1: fastest that still
// compresses). InputError naming the path when it cannot be written.
void write_png_file(const std::filesystem::path& path, const cv::Mat& image, int compression_level = 1);

}  // namespace suite::carving
