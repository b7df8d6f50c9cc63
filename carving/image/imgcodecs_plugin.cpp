// seedcarve's decoder of the image formats other than PNG (JPEG, TIFF, BMP, ...): OpenCV's
// imgcodecs in a module of its own, loaded by image_io.cpp when the first such image is read, so
// that a process reading only PNGs never loads imgcodecs's 140 shared libraries.
#include "carving/image/imgcodecs_plugin.hpp"

#include <cstddef>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

extern "C" int suite_carving_imread(const char* path, cv::Mat* image, char* message, std::size_t message_size) {
  try {
    *image = cv::imread(path, cv::IMREAD_COLOR);
    return image->empty() ? 1 : 0;
  } catch (const cv::Exception& e) {
    std::snprintf(message, message_size, "%s", e.err.c_str());
    return 2;
  }
}
