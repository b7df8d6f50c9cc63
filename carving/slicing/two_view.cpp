// Two-view slicing: volume, length, width and thickness from a top and a side mask (see two_view.hpp).
#include "carving/slicing/two_view.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"

namespace suite::carving {

namespace {

// The two tips of a silhouette along one image axis, in pixel-centre coordinates, from its seed
// pixels per line across that axis (`counts`, first and last the outermost lines with seed).
// The tip lies between the last line with seed and the next one. Near a rounded tip the chord
// length h grows as the square root of the distance from the tip (locally an ellipse: h^2 is
// linear in x), so the line through (x, h^2) of the last two lines meets zero at the tip: at any
// sub-pixel position of the seed, where counting lines assumes the tip half a pixel beyond the last
// one (one pixel too long for a seed whose tips fall on pixel centres). Where the end is not
// rounded (h not falling towards it) the half pixel stays.
struct Ends {
  double lo = 0, hi = 0;
};

double tip(const std::vector<long long>& counts, int last, int inward) {
  const int before = last + inward;
  const double edge = last - 0.5 * inward;  // half a pixel beyond the last line
  if (before < 0 || before >= static_cast<int>(counts.size())) return edge;
  const double h1 = static_cast<double>(counts[static_cast<std::size_t>(last)]);
  const double h2 = static_cast<double>(counts[static_cast<std::size_t>(before)]);
  if (!(h2 > h1)) return edge;
  const double beyond = h1 * h1 / (h2 * h2 - h1 * h1);  // lines past `last` where h^2 reaches 0
  return last - inward * std::min(beyond, 1.0);
}

Ends ends(const std::vector<long long>& counts, int first, int last) {
  return {tip(counts, first, +1), tip(counts, last, -1)};
}

// Seed-pixel counts of every column and row, the box of the seed pixels, and the chord each
// slice takes per column (the counts, or the neighbour-averaged contour extents).
struct Profile {
  std::vector<long long> columns, rows;
  std::vector<double> chords;
  PixelBox box;

  // Chord at a continuous column position, linear between column centres, 0 outside the image.
  double at(double x) const {
    const double lo = std::floor(x);
    const double f = x - lo;
    const auto value = [&](double c) {
      return c >= 0 && c < static_cast<double>(chords.size()) ? chords[static_cast<std::size_t>(c)] : 0.0;
    };
    return (1 - f) * value(lo) + f * value(lo + 1);
  }
};

// The dissertation's smoothing: each column's upper and lower contour points (its first and last
// seed rows) averaged with those of the two columns on each side that hold seed pixels (fewer at
// the tips), the chord being the averaged lower minus the averaged upper point, plus one pixel.
std::vector<double> neighbour_averaged_chords(const Mask& mask, const PixelBox& box) {
  constexpr int kReach = 2;  // 5 points: the column itself and two on each side
  const int n = box.width();
  std::vector<double> upper(static_cast<std::size_t>(n), 0), lower(static_cast<std::size_t>(n), 0);
  std::vector<char> has(static_cast<std::size_t>(n), 0);
  for (int x = box.x0; x <= box.x1; ++x) {
    const auto i = static_cast<std::size_t>(x - box.x0);
    int y0 = box.y0;
    while (y0 <= box.y1 && !mask.at(x, y0)) ++y0;
    if (y0 > box.y1) continue;  // no seed in this column (a mask of several pieces)
    int y1 = box.y1;
    while (!mask.at(x, y1)) --y1;
    upper[i] = y0, lower[i] = y1, has[i] = 1;
  }
  std::vector<double> chords(static_cast<std::size_t>(mask.width()), 0.0);
  for (int i = 0; i < n; ++i) {
    if (!has[static_cast<std::size_t>(i)]) continue;
    double up = 0, low = 0;
    int points = 0;
    for (int j = std::max(0, i - kReach); j <= std::min(n - 1, i + kReach); ++j)
      if (has[static_cast<std::size_t>(j)])
        up += upper[static_cast<std::size_t>(j)], low += lower[static_cast<std::size_t>(j)], ++points;
    chords[static_cast<std::size_t>(box.x0 + i)] = (low - up) / points + 1;
  }
  return chords;
}

Profile profile(const Mask& mask, const char* which, bool neighbour_average) {
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
  p.rows.resize(static_cast<std::size_t>(mask.height()));
  for (int y = 0; y < mask.height(); ++y) {
    p.rows[static_cast<std::size_t>(y)] = mask.count(0, y, mask.width() - 1, y);
    if (p.rows[static_cast<std::size_t>(y)] > 0) p.box.y0 = std::min(p.box.y0, y), p.box.y1 = y;
  }
  if (neighbour_average) {
    p.chords = neighbour_averaged_chords(mask, p.box);
  } else {
    p.chords.assign(p.columns.begin(), p.columns.end());
  }
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
  const Profile t = profile(top, "top-view", options.neighbour_average),
                s = profile(side, "side-view", options.neighbour_average);

  TwoViewResult r;
  r.top_box = t.box;
  r.side_box = s.box;
  const Ends top_x = ends(t.columns, t.box.x0, t.box.x1), side_x = ends(s.columns, s.box.x0, s.box.x1);
  const Ends top_y = ends(t.rows, t.box.y0, t.box.y1), side_y = ends(s.rows, s.box.y0, s.box.y1);
  const double length_top_px = top_x.hi - top_x.lo, length_side_px = side_x.hi - side_x.lo;
  r.scale = options.scale_correction ? length_top_px / length_side_px : 1.0;
  r.px_per_mm_side = options.px_per_mm_top / r.scale;
  r.length_mm = length_top_px / options.px_per_mm_top;
  r.width_mm = (top_y.hi - top_y.lo) / options.px_per_mm_top;
  r.thickness_mm = (side_y.hi - side_y.lo) / r.px_per_mm_side;

  const int n = options.slices;
  const double step_px = length_top_px / n, h_mm = r.length_mm / n;
  const double start_top = top_x.lo, start_side = side_x.lo;
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
