#include "rice/render/dish_renderer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "core/errors.hpp"
#include "rice/render/grade_scale.hpp"

namespace suite::rice {
namespace {

void check_options(const DishOptions& o, std::size_t grains) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw InputError(what);
  };
  require(grains > 0, "render_dish: no grains to draw; give at least one grade");
  require(o.mm_per_px >= 0.002 && o.mm_per_px <= 0.1,
          fmt::format("pixel size {} mm is outside 0.002..0.1 mm (0.02 mm resolves a 0.1 mm crack in 5 pixels)",
                      o.mm_per_px));
  require(o.columns >= 1, fmt::format("columns {}: give at least 1", o.columns));
  require(o.cell_mm >= 10,
          fmt::format("cell {} mm: give at least 10 mm (a wide collar reaches 6 mm from the centre)", o.cell_mm));
  require(o.lighting_gradient >= 0 && o.lighting_gradient <= 0.3,
          fmt::format("lighting gradient {}: give 0..0.3", o.lighting_gradient));
  require(o.blur_mm >= 0 && o.noise_sigma >= 0 && o.touching_pairs >= 0,
          "blur, noise and touching pairs must not be negative");
}

// The grain's union of kernel and gel in its canvas.
cv::Mat footprint(const GrainLayers& L) {
  cv::Mat m;
  cv::bitwise_or(L.kernel, L.gel, m);
  return m;
}

// Whether two canvases placed at their origins share a drawn pixel.
bool overlap(const cv::Mat& a, cv::Point oa, const cv::Mat& b, cv::Point ob) {
  const cv::Rect ra(oa, a.size()), rb(ob, b.size()), both = ra & rb;
  if (both.empty()) return false;
  cv::Mat shared;
  cv::bitwise_and(a(both - oa), b(both - ob), shared);
  return cv::countNonZero(shared) > 0;
}

// Moves the two grains (already oriented alike) apart along the normal of their long axes, one
// pixel at a time from well apart, and stops at the first distance where their outlines touch.
void place_touching(GrainSpec& first, GrainSpec& second, cv::Point2d centre, double mm_per_px) {
  const double t = first.angle_deg * std::numbers::pi / 180;
  const cv::Point2d normal(-std::sin(t), std::cos(t));
  const double px = 1 / mm_per_px;
  auto reach = [&](const GrainSpec& s) { return (0.5 * s.width_mm + s.collar_mm + 0.5) * px; };
  first.centre_px = second.centre_px = centre;
  const GrainLayers a = draw_grain(first, mm_per_px), b = draw_grain(second, mm_per_px);
  const cv::Mat fa = footprint(a), fb = footprint(b);
  int d = static_cast<int>(std::ceil(reach(first) + reach(second)));
  while (d > 0) {
    const cv::Point shift(static_cast<int>(std::lround(d * normal.x)), static_cast<int>(std::lround(d * normal.y)));
    if (overlap(fa, a.origin, fb, b.origin + shift)) break;
    --d;
  }
  first.centre_px = centre - 0.5 * d * normal;
  second.centre_px = centre + 0.5 * d * normal;
  first.touching = second.touching = true;
}

// Blends `layer` (0..255 mask, softened by a Gaussian of sigma_px) towards `level` into `image`.
void blend(cv::Mat& image, const cv::Mat& layer, double sigma_px, const cv::Mat& level) {
  cv::Mat alpha;
  layer.convertTo(alpha, CV_32F, 1.0 / 255);
  if (sigma_px > 0.05) cv::GaussianBlur(alpha, alpha, cv::Size(), sigma_px);
  image += alpha.mul(level - image);
}

void composite(cv::Mat& image, const GrainSpec& s, const GrainLayers& L, double mm_per_px) {
  const cv::Rect canvas(L.origin, L.kernel.size()), inside = canvas & cv::Rect(0, 0, image.cols, image.rows);
  if (inside.empty()) return;
  // Blur on the whole canvas (its margin holds the blurred edge), then copy the part in the frame.
  cv::Mat local = cv::Mat(canvas.size(), CV_32F, cv::Scalar(0));
  image(inside).copyTo(local(inside - L.origin));
  blend(local, L.gel, s.gel_edge_mm / mm_per_px, L.gel_level);
  blend(local, L.kernel, s.kernel_edge_mm / mm_per_px,
        cv::Mat(canvas.size(), CV_32F, cv::Scalar(s.kernel_fraction * s.kernel_level)));
  local(inside - L.origin).copyTo(image(inside));
}

}  // namespace

RenderedDish render_dish(const std::vector<int>& grades, const DishOptions& o, std::mt19937_64& rng) {
  check_options(o, grades.size());
  for (int g : grades) (void)appearance(g);  // InputError for a grade off the scale
  const double px = 1 / o.mm_per_px;

  // Cells: one grain each, or a touching pair of grades 2-5.
  std::vector<std::vector<std::size_t>> cells;
  int pairs = o.touching_pairs;
  for (std::size_t i = 0; i < grades.size(); ++i) {
    if (pairs > 0 && i + 1 < grades.size() && grades[i] <= 5 && grades[i + 1] <= 5) {
      cells.push_back({i, i + 1});
      ++i, --pairs;
    } else {
      cells.push_back({i});
    }
  }
  const int columns = std::min<int>(o.columns, static_cast<int>(cells.size()));
  const int rows = (static_cast<int>(cells.size()) + columns - 1) / columns;
  const int cell = static_cast<int>(std::lround(o.cell_mm * px));
  RenderedDish dish;
  cv::Mat image(rows * cell, columns * cell, CV_32F, cv::Scalar(o.dish_level));

  std::vector<GrainSpec> specs(grades.size());
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const cv::Point2d centre((static_cast<double>(c % columns) + 0.5) * cell,
                             (static_cast<double>(c / columns) + 0.5) * cell);
    if (cells[c].size() == 2) {
      GrainSpec& a = specs[cells[c][0]] = random_grain(grades[cells[c][0]], centre, rng);
      GrainSpec& b = specs[cells[c][1]] = random_grain(grades[cells[c][1]], centre, rng);
      b.angle_deg = a.angle_deg;
      place_touching(a, b, centre, o.mm_per_px);
      continue;
    }
    GrainSpec& s = specs[cells[c][0]] = random_grain(grades[cells[c][0]], centre, rng);
    const double room = std::max(0.0, 0.5 * o.cell_mm - grain_reach_mm(s) - 0.3) * px;
    s.centre_px += cv::Point2d(std::uniform_real_distribution<double>(-room, room)(rng),
                               std::uniform_real_distribution<double>(-room, room)(rng));
  }
  if (o.frame_cut) {
    // A quarter of the kernel's length beyond the right edge.
    GrainSpec& s = specs.back();
    s.centre_px.x = image.cols - 0.25 * s.length_mm * px;
  }

  for (std::size_t i = 0; i < specs.size(); ++i) {
    const GrainLayers layers = draw_grain(specs[i], o.mm_per_px);
    composite(image, specs[i], layers, o.mm_per_px);
    RenderedGrain g;
    g.index = static_cast<int>(i) + 1;
    g.spec = specs[i];
    g.truth = grain_truth(specs[i], layers, o.mm_per_px, o.dish_level);
    const cv::Rect drawn = cv::boundingRect(footprint(layers)) + layers.origin;
    g.cut_by_frame = (drawn & cv::Rect(0, 0, image.cols, image.rows)) != drawn;
    dish.grains.push_back(g);
  }

  // The lamp: a linear gradient of the light across the dish, in a random direction.
  const double heading = std::uniform_real_distribution<double>(0, 2 * std::numbers::pi)(rng);
  const double strength = std::uniform_real_distribution<double>(0, o.lighting_gradient)(rng);
  for (int y = 0; y < image.rows; ++y) {
    auto* row = image.ptr<float>(y);
    const double v = (y - 0.5 * image.rows) / (0.5 * image.rows);
    for (int x = 0; x < image.cols; ++x) {
      const double u = (x - 0.5 * image.cols) / (0.5 * image.cols);
      row[x] *= static_cast<float>(1 + strength * (u * std::cos(heading) + v * std::sin(heading)));
    }
  }
  if (o.blur_mm > 0) cv::GaussianBlur(image, image, cv::Size(), o.blur_mm * px);

  // Colour (a faint warm tint), then sensor noise per channel.
  std::vector<cv::Mat> channels{image * 0.93, image * 0.97, image.clone()};
  cv::Mat colour;
  cv::merge(channels, colour);
  cv::Mat noise(colour.size(), CV_32FC3);
  cv::RNG noise_rng(rng());
  noise_rng.fill(noise, cv::RNG::NORMAL, 0.0, o.noise_sigma);
  colour += noise;
  colour.convertTo(dish.image, CV_8UC3);
  return dish;
}

}  // namespace suite::rice
