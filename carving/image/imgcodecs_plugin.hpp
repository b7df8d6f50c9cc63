#pragma once
// The interface of seedcarve's image-format plugin (imgcodecs_plugin.cpp, built as the module
// libsuite_carving_imgcodecs.so into the build's lib folder).
#include <cstddef>
#include <opencv2/core.hpp>

// Reads `path` with cv::imread(IMREAD_COLOR) into `image`: 0 when read, 1 when OpenCV returned
// no image (not a format it decodes, or corrupt), 2 when it threw (its message in `message`).
extern "C" int suite_carving_imread(const char* path, cv::Mat* image, char* message, std::size_t message_size);

namespace suite::carving {
using ImreadFunction = decltype(&suite_carving_imread);
inline constexpr const char* kImgcodecsPlugin = "libsuite_carving_imgcodecs.so";
}  // namespace suite::carving
