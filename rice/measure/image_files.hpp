#pragma once
// Reading photographs and writing PNGs with OpenCV (imgcodecs). Every failure is an InputError
// that names the file and says what to do.
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

namespace suite::rice {

// The image as 8-bit grey (colour is converted with OpenCV's BGR -> grey weights; 16-bit images
// are scaled to 8 bits). InputError naming the file when it is missing, a folder, empty, or not
// an image OpenCV decodes.
cv::Mat read_grey(const std::filesystem::path& path);

// The photograph as a network with `channels` 1 or 3 takes it: read_grey(), or 8-bit BGR colour.
// InputError naming the file when it cannot be read.
cv::Mat read_for_network(const std::filesystem::path& path, int channels);

// Writes `image` as PNG; InputError naming the path when it cannot.
void write_png(const std::filesystem::path& path, const cv::Mat& image);

// The images to measure: files as given, and a folder's .png, .jpg, .jpeg, .tif, .tiff and .bmp
// files in name order. A name that does not exist is kept, so that its row says so.
std::vector<std::filesystem::path> expand_image_arguments(const std::vector<std::filesystem::path>& targets);

}  // namespace suite::rice
