#pragma once
// A binary silhouette (1 = seed) with its integral image, so the number of seed pixels in any
// axis-aligned rectangle costs four lookups: the whole-cell test of hierarchical carving.
// Pixels are stored row by row: index y * width + x.
#include <cstdint>
#include <vector>

namespace suite::carving {

class Mask {
 public:
  Mask() = default;
  // `pixels` row by row, non-zero = seed.
  Mask(int width, int height, std::vector<std::uint8_t> pixels);

  int width() const { return width_; }
  int height() const { return height_; }
  bool at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x] != 0; }
  // Seed pixel at (x, y), false outside the image.
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_ && at(x, y); }
  const std::vector<std::uint8_t>& pixels() const { return pixels_; }  // 0 or 1
  long long area() const { return count(0, 0, width_ - 1, height_ - 1); }

  // Seed pixels in the inclusive rectangle [x0, x1] x [y0, y1], which must lie in the image.
  long long count(int x0, int y0, int x1, int y1) const {
    const auto w = static_cast<std::size_t>(width_) + 1;
    return sum_[(y1 + 1) * w + (x1 + 1)] - sum_[y0 * w + (x1 + 1)] - sum_[(y1 + 1) * w + x0] + sum_[y0 * w + x0];
  }

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> pixels_;
  std::vector<std::int32_t> sum_;  // (width + 1) x (height + 1) integral image
};

}  // namespace suite::carving
