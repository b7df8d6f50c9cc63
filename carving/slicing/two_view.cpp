// Two-view slicing: volume, length, width and thickness from a top and a side mask (see two_view.hpp).
#include "carving/slicing/two_view.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"

namespace suite::carving {

namespace {

// Seed-pixel counts of every column, and the box of the seed pixels.
struct Profile {
  std::vector<long long> columns;
  PixelBox box;

  // Column count at a continuous column position, linear between column centres, 0 outside the image.
  double at(double x) const {
    const double lo = std::floor(x);
    const double f = x - lo;
    const auto value = [&](double c) {
      return c >= 0 && c < static_cast<double>(columns.size())
                 ? static_cast<double>(columns[static_cast<std::size_t>(c)])
                 : 0.0;
    };
    return (1 - f) * value(lo) + f * value(lo + 1);
  }
};

Profile profile(const Mask& mask, const char* which) {
  if (mask.width() < 1 || mask.area() == 0)
    throw InputError(
        fmt::format("two-view slicing: the {} mask is empty (no seed pixels); check the segmentation of "
                    "the {} image (HSV range, area range)",
                    which, which));
  Profile p;
  p.columns.resize(static_cast<std::size_t>(mask.width()));
  p.box = {mask.width(), mask.height(), -1, -1};
  for (int x = 0; x < mask.width(); ++x) {
    p.columns[static_cast<std::size_t>(x)] = mask.count(x, 0, x, mask.height() - 1);
    if (p.columns[static_cast<std::size_t>(x)] > 0) p.box.x0 = std::min(p.box.x0, x), p.box.x1 = x;
  }
  for (int y = 0; y < mask.height(); ++y)
    if (mask.count(0, y, mask.width() - 1, y) > 0) p.box.y0 = std::min(p.box.y0, y), p.box.y1 = y;
  return p;
}

}  // namespace

TwoViewResult measure_two_view(const Mask& top, const Mask& side, const SlicingOptions& options) {
  if (options.slices < 1 || options.slices > 100000)
    throw InputError(fmt::format("two-view slicing option slices = {}; it must lie in 1..100000 (50 is the default)",
                                 options.slices));
  if (!(options.px_per_mm_top > 0) || !std::isfinite(options.px_per_mm_top))
    throw InputError(
        fmt::format("two-view slicing option px_per_mm_top = {}; it must be positive (calibrate it with "
                    "a reference ball of known diameter)",
                    options.px_per_mm_top));
  const Profile t = profile(top, "top-view"), s = profile(side, "side-view");

  TwoViewResult r;
  r.top_box = t.box;
  r.side_box = s.box;
  const double length_top_px = t.box.width(), length_side_px = s.box.width();
  r.scale = options.scale_correction ? length_top_px / length_side_px : 1.0;
  r.px_per_mm_side = options.px_per_mm_top / r.scale;
  r.length_mm = length_top_px / options.px_per_mm_top;
  r.width_mm = t.box.height() / options.px_per_mm_top;
  r.thickness_mm = s.box.height() / r.px_per_mm_side;

  const int n = options.slices;
  const double step_px = length_top_px / n, h_mm = r.length_mm / n;
  const double start_top = t.box.x0 - 0.5, start_side = s.box.x0 - 0.5;
  r.slices.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    Slice& slice = r.slices[static_cast<std::size_t>(i)];
    slice.top_x_px = start_top + (i + 0.5) * step_px;
    slice.side_x_px = start_side + (slice.top_x_px - start_top) / r.scale;
    slice.a_mm = 0.5 * t.at(slice.top_x_px) / options.px_per_mm_top;
    slice.b_mm = 0.5 * s.at(slice.side_x_px) / r.px_per_mm_side;
    slice.h_mm = h_mm;
    slice.volume_mm3 = std::numbers::pi * slice.a_mm * slice.b_mm * h_mm;
    r.volume_mm3 += slice.volume_mm3;
  }
  return r;
}

double density_mg_per_mm3(double weight_mg, double volume_mm3) {
  if (!(weight_mg > 0) || !std::isfinite(weight_mg))
    throw InputError(fmt::format("seed weight = {} mg; it must be a positive number of milligrams", weight_mg));
  if (!(volume_mm3 > 0) || !std::isfinite(volume_mm3))
    throw InputError(fmt::format("seed volume = {} mm^3; a density needs a positive volume", volume_mm3));
  return weight_mg / volume_mm3;
}

}  // namespace suite::carving
