#include "carving/image/image_io.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "carving/image/imgcodecs_plugin.hpp"
#include "carving/image/png_codec.hpp"
#include "core/errors.hpp"
#include "core/run/executable_path.hpp"

namespace suite::carving {
namespace {

// The plugin's reader, from the build's or installation's lib folder beside the executable's
// bin folder, or the executable's own folder. dlopen hands back the same handle on every call
// after the first (the plugin stays loaded for the process's life).
ImreadFunction imgcodecs_reader(const std::filesystem::path& image) {
  const std::filesystem::path bin = executable_dir();
  std::vector<std::string> tried;
  for (const auto& candidate : {bin.parent_path() / "lib" / kImgcodecsPlugin, bin / kImgcodecsPlugin}) {
    if (void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      if (auto* read = reinterpret_cast<ImreadFunction>(dlsym(handle, "suite_carving_imread"))) return read;
    }
    const char* why = dlerror();
    tried.push_back(fmt::format("'{}'{}{}", candidate.string(), why ? ": " : "", why ? why : ""));
  }
  throw InputError(
      fmt::format("cannot read image '{}': it is not a PNG, and the reader of other formats could not be loaded ({}); "
                  "keep the lib folder beside the bin folder as built or installed, or convert the images to PNG",
                  image.string(), fmt::join(tried, "; ")));
}

}  // namespace

cv::Mat read_image(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("cannot read image '{}': no such file", path.string()));
  if (auto png = read_png_bgr(path)) return std::move(*png);
  cv::Mat image;
  std::array<char, 512> detail{};
  const int failed = imgcodecs_reader(path)(path.c_str(), &image, detail.data(), detail.size());
  if (failed || image.empty())
    throw InputError(
        fmt::format("cannot read image '{}': empty, corrupt or not a format OpenCV decodes (PNG, JPEG, "
                    "TIFF, BMP){}{}",
                    path.string(), detail[0] ? "; OpenCV: " : "", detail.data()));
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
  write_png_file(path, image);
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
