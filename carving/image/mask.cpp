#include "carving/image/mask.hpp"

#include <stdexcept>

namespace suite::carving {

Mask::Mask(int width, int height, std::vector<std::uint8_t> pixels)
    : width_(width), height_(height), pixels_(std::move(pixels)) {
  if (width < 1 || height < 1 || pixels_.size() != static_cast<std::size_t>(width) * height)
    throw std::invalid_argument("Mask: pixel count does not match width x height");
  for (auto& p : pixels_) p = p ? 1 : 0;
  const std::size_t w = static_cast<std::size_t>(width) + 1;
  sum_.assign(w * (height + 1), 0);
  for (int y = 0; y < height; ++y) {
    std::int32_t row = 0;
    for (int x = 0; x < width; ++x) {
      row += pixels_[static_cast<std::size_t>(y) * width + x];
      sum_[(y + 1) * w + (x + 1)] = sum_[y * w + (x + 1)] + row;
    }
  }
}

}  // namespace suite::carving
