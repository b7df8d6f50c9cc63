#pragma once
// A binary silhouette (1 = seed) with its integral image, so the number of seed pixels in any
// axis-aligned rectangle costs four lookups: the whole-cell test of hierarchical carving.
// Pixels are stored row by row: index y * width + x. The integral image covers only the box of
// the seed pixels (outside it there are none): a seed fills a few percent of a frame, and the
// whole frame's integral image was a tenth of a seed's measurement time.
#include <algorithm>
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

  // The inclusive box of the seed pixels: none lie outside it (empty when x1 < x0).
  struct Box {
    int x0, y0, x1, y1;
  };
  Box seed_box() const { return {box_x0_, box_y0_, box_x1_, box_y1_}; }

  // Seed pixels in the inclusive rectangle [x0, x1] x [y0, y1], which must lie in the image.
  long long count(int x0, int y0, int x1, int y1) const {
    x0 = std::max(x0, box_x0_) - box_x0_, y0 = std::max(y0, box_y0_) - box_y0_;
    x1 = std::min(x1, box_x1_) - box_x0_, y1 = std::min(y1, box_y1_) - box_y0_;
    if (x0 > x1 || y0 > y1) return 0;
    const auto w = static_cast<std::size_t>(box_x1_ - box_x0_) + 2;
    const auto ux0 = static_cast<std::size_t>(x0), uy0 = static_cast<std::size_t>(y0);
    const auto ux1 = static_cast<std::size_t>(x1) + 1, uy1 = static_cast<std::size_t>(y1) + 1;
    return sum_[uy1 * w + ux1] - sum_[uy0 * w + ux1] - sum_[uy1 * w + ux0] + sum_[uy0 * w + ux0];
  }

 private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> pixels_;
  int box_x0_ = 0, box_y0_ = 0, box_x1_ = -1, box_y1_ = -1;  // the seed pixels' box (empty: x1 < x0)
  std::vector<std::int32_t> sum_;  // (box width + 1) x (box height + 1) integral image
};

}  // namespace suite::carving
