#include "rice/measure/grain_traits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "core/errors.hpp"

namespace suite::rice {
namespace {

void check_options(const MeasureOptions& o) {
  if (!(o.mm_per_px > 0) || o.mm_per_px > 1)
    throw InputError(
        fmt::format("pixel size {} mm: give the size of one pixel on the dish in mm, in (0, 1] (e.g. "
                    "--pixel-size 0.02)",
                    o.mm_per_px));
  if (o.angular_bins < 8) throw InputError(fmt::format("angular bins {}: give at least 8", o.angular_bins));
  if (o.min_grain_mm2 < 0 || o.min_piece_mm2 < 0 || o.gel_opening_mm < 0)
    throw InputError("minimum areas and the gel opening must not be negative");
}

void add_flag(GrainTraits& g, const std::string& flag) {
  g.ok = false;
  g.quality += (g.quality.empty() ? "" : ";") + flag;
}

// The traits of component `label` inside its bounding box `box`.
GrainTraits grain_traits(const cv::Mat& grey, const ImageTraits& image, int label, const cv::Rect& box,
                         const MeasureOptions& o) {
  const double pixel_area = o.mm_per_px * o.mm_per_px;
  const cv::Mat inside = image.labels(box) == label;
  cv::Mat kernel, gel;
  cv::bitwise_and(image.kernel(box), inside, kernel);
  cv::bitwise_and(image.gel(box), inside, gel);
  GrainTraits g;
  g.grain_area_mm2 = cv::countNonZero(inside) * pixel_area;

  // Kernel pieces: components of at least min_piece_mm2.
  cv::Mat piece_labels, piece_stats, piece_centroids;
  const int n = cv::connectedComponentsWithStats(kernel, piece_labels, piece_stats, piece_centroids, 8);
  cv::Mat pieces = cv::Mat::zeros(kernel.size(), CV_8U);
  int whole_kernels = 0;
  for (int p = 1; p < n; ++p) {
    if (piece_stats.at<int>(p, cv::CC_STAT_AREA) * pixel_area < o.min_piece_mm2) continue;
    const cv::Mat piece = piece_labels == p;
    pieces.setTo(255, piece);
    ++g.kernel_pieces;
    std::vector<cv::Point> points;
    cv::findNonZero(piece, points);
    const cv::RotatedRect r = cv::minAreaRect(points);
    const double length = (std::max(r.size.width, r.size.height) + 1) * o.mm_per_px;
    if (length >= o.whole_kernel_mm) ++whole_kernels;
  }
  const int kernel_pixels = cv::countNonZero(pieces);
  g.kernel_area_mm2 = kernel_pixels * pixel_area;
  g.gel_area_mm2 = cv::countNonZero(gel) * pixel_area;

  // Centre: the kernel's centroid, or the grain's.
  const cv::Moments m = cv::moments(kernel_pixels > 0 ? pieces : inside, true);
  const cv::Point2d centre(m.m10 / m.m00, m.m01 / m.m00);
  g.x_px = box.x + centre.x;
  g.y_px = box.y + centre.y;

  if (kernel_pixels > 0) {
    std::vector<cv::Point> points, hull;
    cv::findNonZero(pieces, points);
    cv::convexHull(points, hull);
    g.kernel_solidity = std::min(1.0, kernel_pixels / std::max(1.0, cv::contourArea(hull)));
    const cv::RotatedRect r = cv::minAreaRect(points);
    g.kernel_length_mm = (std::max(r.size.width, r.size.height) + 1) * o.mm_per_px;
    g.kernel_width_mm = (std::min(r.size.width, r.size.height) + 1) * o.mm_per_px;
    g.gel_kernel_ratio = g.gel_area_mm2 / g.kernel_area_mm2;
    if (whole_kernels >= 2 || g.kernel_width_mm > o.max_kernel_width_mm) add_flag(g, "touching");
  } else {
    g.kernel_solidity = g.gel_kernel_ratio = std::nan("");
  }

  // Collar completeness: directions from the centre that hold a gel pixel.
  std::vector<char> hit(static_cast<std::size_t>(o.angular_bins), 0);
  std::vector<cv::Point> gel_points;
  cv::findNonZero(gel, gel_points);
  for (const auto& p : gel_points) {
    const double angle = std::atan2(p.y - centre.y, p.x - centre.x) + std::numbers::pi;
    const auto bin = static_cast<std::size_t>(angle / (2 * std::numbers::pi) * o.angular_bins) % hit.size();
    hit[bin] = 1;
  }
  g.collar_completeness = static_cast<double>(std::count(hit.begin(), hit.end(), 1)) / o.angular_bins;

  // Kernel share of the brightness above the dish.
  cv::Mat above;
  grey(box).convertTo(above, CV_64F, 1.0, -image.levels.dish);
  cv::Mat grain_weight, kernel_weight;
  inside.convertTo(grain_weight, CV_64F, 1.0 / 255);
  const double total = cv::sum(above.mul(grain_weight))[0];
  pieces.convertTo(kernel_weight, CV_64F, 1.0 / 255);
  const double kernel_mass = cv::sum(above.mul(kernel_weight))[0];
  g.kernel_share = total > 0 ? kernel_mass / total : 0;

  // The frame.
  if (box.x == 0 || box.y == 0 || box.x + box.width == grey.cols || box.y + box.height == grey.rows)
    add_flag(g, "cut_by_frame");
  return g;
}

}  // namespace

ImageTraits measure_grains(const cv::Mat& grey, const MeasureOptions& o) {
  check_options(o);
  ImageTraits image;
  image.levels = dish_levels(grey, o.levels);
  const DishLevels& L = image.levels;
  cv::Mat grain = grey > L.grain_threshold;
  image.kernel = L.kernel_threshold < 256 ? (grey > L.kernel_threshold) : cv::Mat::zeros(grey.size(), CV_8U);
  cv::bitwise_and(image.kernel, grain, image.kernel);
  cv::bitwise_and(grain, ~image.kernel, image.gel);
  const int opening = std::max(3, 2 * static_cast<int>(std::lround(0.5 * o.gel_opening_mm / o.mm_per_px)) + 1);
  cv::morphologyEx(image.gel, image.gel, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(opening, opening)));

  cv::Mat stats, centroids;
  const int n = cv::connectedComponentsWithStats(grain, image.labels, stats, centroids, 8, CV_32S);
  const double pixel_area = o.mm_per_px * o.mm_per_px;
  for (int label = 1; label < n; ++label) {
    if (stats.at<int>(label, cv::CC_STAT_AREA) * pixel_area < o.min_grain_mm2) continue;
    const cv::Rect box(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                       stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    GrainTraits g = grain_traits(grey, image, label, box, o);
    g.grain = static_cast<int>(image.grains.size()) + 1;
    image.grains.push_back(g);
  }
  return image;
}

}  // namespace suite::rice
