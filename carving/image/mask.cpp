#include "carving/image/mask.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>

namespace suite::carving {

Mask::Mask(int width, int height, std::vector<std::uint8_t> pixels)
    : width_(width), height_(height), pixels_(std::move(pixels)) {
  if (width < 1 || height < 1 || pixels_.size() != static_cast<std::size_t>(width) * height)
    throw std::invalid_argument("Mask: pixel count does not match width x height");
  for (auto& p : pixels_) p = p ? 1 : 0;
  box_x0_ = width, box_y0_ = height, box_x1_ = -1, box_y1_ = -1;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = pixels_.data() + static_cast<std::size_t>(y) * width;
    const auto* first = std::find(row, row + width, 1);
    if (first == row + width) continue;
    const auto last = std::find(std::make_reverse_iterator(row + width), std::make_reverse_iterator(row), 1);
    box_x0_ = std::min(box_x0_, static_cast<int>(first - row));
    box_x1_ = std::max(box_x1_, static_cast<int>(last.base() - row) - 1);
    box_y0_ = std::min(box_y0_, y);
    box_y1_ = y;
  }
  if (box_x1_ < 0) {  // no seed pixel
    box_x0_ = box_y0_ = 0;
    return;
  }
  const int bw = box_x1_ - box_x0_ + 1, bh = box_y1_ - box_y0_ + 1;
  const std::size_t w = static_cast<std::size_t>(bw) + 1;
  sum_.assign(w * static_cast<std::size_t>(bh + 1), 0);
  for (int y = 0; y < bh; ++y) {
    const std::uint8_t* row = pixels_.data() + static_cast<std::size_t>(y + box_y0_) * width + box_x0_;
    std::int32_t run = 0;
    for (int x = 0; x < bw; ++x) {
      run += row[x];
      sum_[(y + 1) * w + (x + 1)] = sum_[y * w + (x + 1)] + run;
    }
  }
}

}  // namespace suite::carving
