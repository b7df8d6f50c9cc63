// Turntable axis from a full turn of silhouettes, and crop-to-frame registration (see the header).
#include "carving/calibration/turntable_axis.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "carving/hull/carver.hpp"
#include "core/errors.hpp"

namespace suite::carving {
namespace {

struct Silhouette {
  double centroid_x = 0;
  double centre_y = 0;  // bounding-box centre row
  int bottom = 0;
};

Silhouette measure(const Mask& mask, std::size_t view) {
  double sum_x = 0;
  long long count = 0;
  int top = mask.height(), bottom = -1;
  for (int y = 0; y < mask.height(); ++y)
    for (int x = 0; x < mask.width(); ++x)
      if (mask.at(x, y)) {
        sum_x += x;
        ++count;
        top = std::min(top, y);
        bottom = std::max(bottom, y);
      }
  if (count == 0)
    throw InputError(
        fmt::format("turntable axis: the mask of view {} has no seed pixels; every view must show the "
                    "seed",
                    view));
  return {sum_x / static_cast<double>(count), 0.5 * (top + bottom), bottom};
}

// Least-squares fit of x = column + sum_k (a_k cos k t + b_k sin k t) over the odd k up to
// 2 * harmonics - 1, and k = 2 when `perspective`. Returns false when the angles do not determine
// the coefficients.
bool fit_centroids(const std::vector<double>& x, const std::vector<double>& angles, int harmonics, bool perspective,
                   AxisEstimate& out) {
  const int n = static_cast<int>(x.size());
  std::vector<double> ks;
  for (int h = 0; h < harmonics; ++h) ks.push_back(2 * h + 1);
  if (perspective) ks.push_back(2);
  const int p = 1 + 2 * static_cast<int>(ks.size());
  Eigen::MatrixXd A(n, p);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    A(i, 0) = 1;
    for (std::size_t j = 0; j < ks.size(); ++j) {
      A(i, 1 + 2 * static_cast<int>(j)) = std::cos(ks[j] * angles[i]);
      A(i, 2 + 2 * static_cast<int>(j)) = std::sin(ks[j] * angles[i]);
    }
    b(i) = x[i];
  }
  // Column-scaled QR: the angles fix the coefficients when A has full rank (singular directions
  // appear when all angles lie close together, or sit at multiples of 2 pi / 3 for k = 3).
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  qr.setThreshold(1e-6);
  if (qr.rank() < p) return false;
  const Eigen::VectorXd c = qr.solve(b);
  const Eigen::MatrixXd N = A.transpose() * A;
  const Eigen::VectorXd r = A * c - b;
  const double rss = r.squaredNorm();
  out.column = c(0);
  out.residual_px = std::sqrt(rss / n);
  out.column_stderr_px = n > p ? std::sqrt(rss / (n - p) * N.inverse()(0, 0)) : 0.0;
  out.orbit_radius_px = std::hypot(c(1), c(2));
  out.harmonics = harmonics;
  out.perspective_term = perspective;
  return true;
}

}  // namespace

AxisEstimate estimate_axis(const std::vector<Mask>& masks, const std::vector<double>& angles_rad) {
  if (masks.size() != angles_rad.size())
    throw InputError(fmt::format("turntable axis: {} masks but {} angles; give one angle per mask", masks.size(),
                                 angles_rad.size()));
  if (masks.size() < 3)
    throw InputError(
        fmt::format("turntable axis: {} views; give at least 3 views spread over the turn (a full turn "
                    "of equally spaced views is best)",
                    masks.size()));
  std::vector<double> x;
  AxisEstimate est;
  for (std::size_t v = 0; v < masks.size(); ++v) {
    if (masks[v].width() != masks[0].width() || masks[v].height() != masks[0].height())
      throw InputError(
          fmt::format("turntable axis: view {} is {} x {} px but view 0 is {} x {} px; all frames must "
                      "have one size",
                      v, masks[v].width(), masks[v].height(), masks[0].width(), masks[0].height()));
    if (!std::isfinite(angles_rad[v]))
      throw InputError(
          fmt::format("turntable axis: the angle of view {} is {}; give a finite angle in radians", v, angles_rad[v]));
    const Silhouette s = measure(masks[v], v);
    x.push_back(s.centroid_x);
    est.row += s.centre_y / static_cast<double>(masks.size());
    est.base_row = std::max(est.base_row, static_cast<double>(s.bottom));
  }
  // Odd harmonics k = 1, 3, ..., 2h - 1 with h as large as leaves at least half the observations
  // to the residual (at most k = 9), and the perspective term k = 2 from 12 views on; fewer terms
  // when the angles cannot tell them apart.
  const int n = static_cast<int>(masks.size());
  const int h_max = std::clamp((n / 2 - 1) / 2, 1, 5);
  bool fitted = false;
  for (int h = h_max; h >= 1 && !fitted; --h) {
    if (n >= 12) fitted = fit_centroids(x, angles_rad, h, true, est);
    if (!fitted) fitted = fit_centroids(x, angles_rad, h, false, est);
  }
  if (!fitted)
    throw InputError(
        fmt::format("turntable axis: the {} view angles do not fix the axis (they are too close together); "
                    "give views spread over at least half a turn",
                    masks.size()));
  return est;
}

Eigen::Matrix3d CropPlacement::matrix() const {
  Eigen::Matrix3d A;
  A << (mirrored ? -scale : scale), 0, x0, 0, scale, y0, 0, 0, 1;
  return A;
}

std::vector<View> place_views(const std::vector<View>& calibrated, const CropPlacement& placement, int frame_width,
                              int frame_height) {
  if (!(placement.scale > 0) || !std::isfinite(placement.scale))
    throw InputError(fmt::format("crop placement: scale {} is not valid; give the frame pixels per crop pixel (> 0)",
                                 placement.scale));
  if (!std::isfinite(placement.x0) || !std::isfinite(placement.y0))
    throw InputError(fmt::format("crop placement: origin ({}, {}) is not finite", placement.x0, placement.y0));
  if (frame_width <= 0 || frame_height <= 0)
    throw InputError(fmt::format("crop placement: frame size {} x {} px; give a positive width and height", frame_width,
                                 frame_height));
  const Eigen::Matrix3d A = placement.matrix();
  std::vector<View> out;
  out.reserve(calibrated.size());
  for (const View& v : calibrated) out.push_back({A * v.P, frame_width, frame_height});
  return out;
}

std::vector<View> shift_views(const std::vector<View>& calibrated, double x0, double y0, int frame_width,
                              int frame_height) {
  return place_views(calibrated, CropPlacement{x0, y0, 1.0, false}, frame_width, frame_height);
}

Registration register_to_frames(const std::vector<Mask>& frame_masks, const std::vector<View>& crop_views,
                                const std::vector<double>& angles_rad, const RegistrationOptions& options) {
  if (crop_views.size() != frame_masks.size())
    throw InputError(fmt::format("registration: {} crop views but {} frame masks; give one calibrated view per frame",
                                 crop_views.size(), frame_masks.size()));
  if (options.orientation < -1 || options.orientation > 1)
    throw InputError(
        fmt::format("registration: orientation {}; give +1 (same sense as the crops), -1 (opposite) or 0 "
                    "(decide from the hull volume)",
                    options.orientation));
  if (!(options.refine_half_width_px >= 0) || !(options.refine_step_px > 0))
    throw InputError(
        fmt::format("registration: refine_half_width_px {} and refine_step_px {}; give a half width >= 0 "
                    "and a step > 0",
                    options.refine_half_width_px, options.refine_step_px));
  const bool carves = options.orientation == 0 || options.refine_half_width_px > 0;
  if (carves && options.grid.count() <= 0)
    throw InputError(
        "registration: choosing the sense of rotation or refining the axis column carves the frames; give "
        "a non-empty grid (e.g. a 10 mm cube at 100^3 about the origin for a wheat grain)");

  Registration reg;
  reg.axis = estimate_axis(frame_masks, angles_rad);  // checks counts and sizes of the masks
  const int width = frame_masks[0].width(), height = frame_masks[0].height();

  // Where the crops see the world origin (on the axis): the same pixel in every view.
  for (std::size_t v = 0; v < crop_views.size(); ++v) {
    const Projection& P = crop_views[v].P;
    if (!(P(2, 3) > 0))
      throw InputError(
          fmt::format("registration: crop view {} puts the world origin at depth {}; the origin (on the "
                      "turntable axis) must lie in front of every camera",
                      v, P(2, 3)));
    const double u = P(0, 3) / P(2, 3), w = P(1, 3) / P(2, 3);
    if (v == 0) {
      reg.crop_axis_column = u;
      reg.crop_origin_row = w;
    } else if (std::abs(u - reg.crop_axis_column) > 0.01 || std::abs(w - reg.crop_origin_row) > 0.01) {
      throw InputError(
          fmt::format("registration: crop view {} sees the world origin at ({:.3f}, {:.3f}) but view 0 at "
                      "({:.3f}, {:.3f}); a turntable calibration sees the origin at one pixel in every view",
                      v, u, w, reg.crop_axis_column, reg.crop_origin_row));
    }
  }

  const auto placement_for = [&](double column, bool mirrored) {
    CropPlacement p;
    p.scale = options.scale;
    p.mirrored = mirrored;
    p.x0 = column - (mirrored ? -options.scale : options.scale) * reg.crop_axis_column;
    p.y0 = reg.axis.row - options.scale * reg.crop_origin_row;
    return p;
  };
  const auto volume_for = [&](const CropPlacement& p) {
    return carve(place_views(crop_views, p, width, height), frame_masks, options.grid).volume_mm3;
  };

  reg.column = reg.axis.column;
  bool mirrored = options.orientation < 0;
  if (options.orientation == 0) {
    const double same = volume_for(placement_for(reg.column, false));
    const double other = volume_for(placement_for(reg.column, true));
    mirrored = other > same;
    reg.volume_mm3 = std::max(same, other);
    reg.other_sense_volume_mm3 = std::min(same, other);
  }
  if (options.refine_half_width_px > 0) {
    const int steps = static_cast<int>(std::floor(options.refine_half_width_px / options.refine_step_px + 1e-9));
    double best_column = reg.axis.column, best_volume = -1;
    for (int i = -steps; i <= steps; ++i) {
      const double column = reg.axis.column + i * options.refine_step_px;
      const double volume = volume_for(placement_for(column, mirrored));
      // Ties keep the column nearest the centroid estimate.
      if (volume > best_volume ||
          (volume == best_volume && std::abs(column - reg.axis.column) < std::abs(best_column - reg.axis.column))) {
        best_volume = volume;
        best_column = column;
      }
    }
    reg.column = best_column;
    reg.volume_mm3 = best_volume;
  }
  reg.placement = placement_for(reg.column, mirrored);
  reg.views = place_views(crop_views, reg.placement, width, height);
  return reg;
}

}  // namespace suite::carving
