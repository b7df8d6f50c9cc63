#include "rice/measure/image_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "core/errors.hpp"

namespace suite::rice {

cv::Mat read_grey(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("cannot read image '{}': it is a folder; give the images in it (e.g. '{}/*.png')",
                                 path.string(), path.string()));
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(
        fmt::format("cannot read image '{}': no such file; check the path and the file name", path.string()));
  if (std::filesystem::file_size(path, ec) == 0)
    throw InputError(
        fmt::format("cannot read image '{}': the file is empty (0 bytes); copy or export the photograph "
                    "again",
                    path.string()));
  cv::Mat image;
  std::string detail;
  try {
    image = cv::imread(path.string(), cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  } catch (const cv::Exception& e) {
    detail = e.err;
  }
  if (image.empty() || image.cols == 0 || image.rows == 0)
    throw InputError(
        fmt::format("cannot read image '{}': corrupt or not a format OpenCV decodes; save it as PNG, "
                    "JPEG, TIFF or BMP{}{}",
                    path.string(), detail.empty() ? "" : "; OpenCV: ", detail));
  if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 257);
  if (image.depth() != CV_8U)
    throw InputError(fmt::format("cannot read image '{}': {}-bit samples; save it with 8 or 16 bits per channel",
                                 path.string(), 8 * static_cast<int>(image.elemSize1())));
  cv::Mat grey;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else if (image.channels() == 4)
    cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
  else
    grey = image;
  return grey;
}

cv::Mat read_for_network(const std::filesystem::path& path, int channels) {
  if (channels == 1) return read_grey(path);
  const cv::Mat image = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (image.empty())
    throw InputError(
        fmt::format("cannot read image '{}' in colour for the network; save it as PNG or JPEG", path.string()));
  return image;
}

void write_png(const std::filesystem::path& path, const cv::Mat& image) {
  bool ok = false;
  std::string detail;
  try {
    ok = !image.empty() && cv::imwrite(path.string(), image);
  } catch (const cv::Exception& e) {
    detail = e.err;
  }
  if (!ok)
    throw InputError(fmt::format("cannot write image '{}': check that its folder exists and is writable{}{}",
                                 path.string(), detail.empty() ? "" : "; OpenCV: ", detail));
}

std::vector<std::filesystem::path> expand_image_arguments(const std::vector<std::filesystem::path>& targets) {
  static const std::vector<std::string> extensions = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp"};
  std::vector<std::filesystem::path> images;
  for (const auto& t : targets) {
    std::error_code ec;
    if (!std::filesystem::is_directory(t, ec)) {
      images.push_back(t);
      continue;
    }
    std::vector<std::filesystem::path> inside;
    for (const auto& entry : std::filesystem::directory_iterator(t, ec)) {
      std::string ext = entry.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (entry.is_regular_file() && std::find(extensions.begin(), extensions.end(), ext) != extensions.end())
        inside.push_back(entry.path());
    }
    std::sort(inside.begin(), inside.end());
    if (inside.empty())
      throw InputError(
          fmt::format("folder '{}' holds no images (.png, .jpg, .tif, .bmp); give image files or a folder "
                      "of them",
                      t.string()));
    images.insert(images.end(), inside.begin(), inside.end());
  }
  return images;
}

}  // namespace suite::rice
