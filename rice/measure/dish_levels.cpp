#include "rice/measure/dish_levels.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/errors.hpp"

namespace suite::rice {
namespace {

using Histogram = std::array<double, 256>;

// The grey level below which `fraction` of the histogram's mass in [from, to] lies.
double quantile(const Histogram& h, int from, int to, double fraction) {
  double total = 0;
  for (int v = from; v <= to; ++v) total += h[v];
  double seen = 0;
  for (int v = from; v <= to; ++v) {
    seen += h[v];
    if (seen >= fraction * total) return v;
  }
  return to;
}

struct ClassStats {
  double weight = 0, mean = 0, variance = 0;
};

ClassStats stats(const Histogram& h, int from, int to) {
  ClassStats s;
  for (int v = from; v <= to; ++v) s.weight += h[v], s.mean += v * h[v];
  if (s.weight <= 0) return s;
  s.mean /= s.weight;
  for (int v = from; v <= to; ++v) s.variance += h[v] * (v - s.mean) * (v - s.mean);
  s.variance /= s.weight;
  return s;
}

}  // namespace

DishLevels dish_levels(const cv::Mat& grey, const LevelOptions& o) {
  if (grey.empty() || grey.type() != CV_8UC1)
    throw InputError(
        fmt::format("dish_levels: the image is {} x {} of OpenCV type {}; give a non-empty 8-bit grey "
                    "image",
                    grey.cols, grey.rows, grey.type()));
  Histogram h{};
  for (int y = 0; y < grey.rows; ++y) {
    const auto* row = grey.ptr<std::uint8_t>(y);
    for (int x = 0; x < grey.cols; ++x) h[row[x]] += 1;
  }
  DishLevels L;
  L.dish = quantile(h, 0, 255, 0.5);
  Histogram deviation{};
  for (int v = 0; v < 256; ++v) deviation[static_cast<int>(std::abs(v - L.dish))] += h[v];
  L.noise = 1.4826 * std::max(0.5, quantile(deviation, 0, 255, 0.5));
  const int first = static_cast<int>(std::ceil(L.dish + std::max(6 * L.noise, o.min_contrast)));
  L.populations = "none";
  if (first > 255) return L;
  const ClassStats grain = stats(h, first, 255);
  if (grain.weight <= 0) return L;

  // The histogram of the flat pixels (the populations' plateaus).
  cv::Mat smooth, dx, dy;
  grey.convertTo(smooth, CV_32F);
  cv::GaussianBlur(smooth, smooth, cv::Size(), 1.0);
  cv::Sobel(smooth, dx, CV_32F, 1, 0, 3, 1.0 / 8);
  cv::Sobel(smooth, dy, CV_32F, 0, 1, 3, 1.0 / 8);
  const double flat = o.flat_slope * (255 - L.dish);
  Histogram hf{};
  for (int y = 0; y < grey.rows; ++y) {
    const auto* v = grey.ptr<std::uint8_t>(y);
    const auto* gx = dx.ptr<float>(y);
    const auto* gy = dy.ptr<float>(y);
    for (int x = 0; x < grey.cols; ++x)
      if (v[x] >= first && gx[x] * gx[x] + gy[x] * gy[x] < flat * flat) hf[v[x]] += 1;
  }
  const ClassStats flat_grain = stats(hf, first, 255);
  if (flat_grain.weight <= 0) hf = h;

  // Otsu's threshold (OpenCV's) over those levels: the last level of the lower class.
  std::vector<std::uint8_t> levels;
  for (int v = first; v < 256; ++v) levels.insert(levels.end(), static_cast<std::size_t>(hf[v]), static_cast<std::uint8_t>(v));
  cv::Mat level_row(1, static_cast<int>(levels.size()), CV_8U, levels.data()), split;
  const int t = static_cast<int>(cv::threshold(level_row, split, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
  const ClassStats low = stats(hf, first, t), high = stats(hf, t + 1, 255);
  L.separation = (high.mean - low.mean) / std::sqrt(0.5 * (low.variance + high.variance) + 1e-12);
  const double low_median = quantile(hf, first, t, 0.5), high_median = quantile(hf, t + 1, 255, 0.5);
  L.contrast = (high_median - L.dish) / std::max(1.0, low_median - L.dish);
  const bool two = L.contrast >= o.contrast && L.separation > o.separation &&
                   std::min(low.weight, high.weight) >= o.min_class_share * (low.weight + high.weight);
  if (two) {
    L.gel = low_median;
    L.kernel = high_median;
    L.grain_threshold = 0.5 * (L.dish + L.gel);
    L.kernel_threshold = 0.5 * (L.gel + L.kernel);
    L.populations = "gel and kernel";
    return L;
  }
  const double level = quantile(hf, first, 255, 0.5);
  L.grain_threshold = 0.5 * (L.dish + level);
  if (level - L.dish >= 0.5 * (255 - L.dish)) {
    L.kernel = level;
    L.kernel_threshold = L.grain_threshold;
    L.populations = "kernel";
  } else {
    L.gel = level;
    L.populations = "gel";
  }
  return L;
}

}  // namespace suite::rice
