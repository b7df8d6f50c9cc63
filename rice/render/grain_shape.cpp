#include "rice/render/grain_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "rice/render/grade_scale.hpp"

namespace suite::rice {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr int kShift = 4;  // fractional bits of OpenCV's sub-pixel drawing (1/16 pixel)
constexpr double kSubpixel = 1 << kShift;

double uniform(std::mt19937_64& rng, double low, double high) {
  return high > low ? std::uniform_real_distribution<double>(low, high)(rng) : low;
}
double uniform(std::mt19937_64& rng, const Range& r) {
  return uniform(rng, r.low, r.high);
}

// sign(v) |v|^p: the superellipse's parametrisation.
double signed_power(double v, double p) {
  return std::copysign(std::pow(std::abs(v), p), v);
}

cv::Point fixed_point(cv::Point2d p) {
  return {static_cast<int>(std::lround(p.x * kSubpixel)), static_cast<int>(std::lround(p.y * kSubpixel))};
}

void fill_polygon(cv::Mat& mask, const std::vector<cv::Point2d>& points, int value) {
  std::vector<cv::Point> fixed;
  fixed.reserve(points.size());
  for (const auto& p : points) fixed.push_back(fixed_point(p));
  cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{fixed}, cv::Scalar(value), cv::LINE_8, kShift);
}

// A grain-frame offset (mm, x along the long axis) as an image offset in pixels.
cv::Point2d grain_offset(const GrainSpec& s, double dx_mm, double dy_mm, double px_per_mm) {
  const double c = std::cos(s.angle_deg * kDegree), n = std::sin(s.angle_deg * kDegree);
  return {(c * dx_mm - n * dy_mm) * px_per_mm, (n * dx_mm + c * dy_mm) * px_per_mm};
}

// Smooth random field of unit-order amplitude: Gaussian noise on a coarse grid (one value per
// `cell_px`), resized with cubic interpolation.
cv::Mat low_frequency_noise(cv::Size size, double cell_px, std::uint64_t seed) {
  const cv::Size coarse(std::max(2, static_cast<int>(size.width / cell_px) + 2),
                        std::max(2, static_cast<int>(size.height / cell_px) + 2));
  cv::Mat small(coarse, CV_32F);
  cv::RNG rng(seed);
  rng.fill(small, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat field;
  cv::resize(small, field, size, 0, 0, cv::INTER_CUBIC);
  return field;
}

}  // namespace

GrainSpec random_grain(int grade, cv::Point2d centre_px, std::mt19937_64& rng) {
  const GradeAppearance& g = appearance(grade);
  GrainSpec s;
  s.grade = grade;
  s.centre_px = centre_px;
  s.angle_deg = uniform(rng, 0, 180);
  const double swelling = uniform(rng, g.swelling);
  // Milled long- and medium-grain rice: 5-7 mm long, 2-2.5 mm wide (before soaking).
  s.length_mm = uniform(rng, 5.0, 7.0) * swelling;
  s.width_mm = uniform(rng, 2.0, 2.5) * swelling;
  s.kernel_level = uniform(rng, 195, 230);
  s.gel_level = uniform(rng, 80, 105);
  s.gel_texture = uniform(rng, 0.03, 0.08);
  s.kernel_edge_mm = uniform(rng, 0.010, 0.018);
  s.gel_edge_mm = uniform(rng, 0.015, 0.030);
  s.texture_seed = rng();
  if (g.collar_width_mm.high > 0) {
    if (uniform(rng, 0, 1) < g.narrow_share) {
      s.collar_mm = uniform(rng, g.narrow_width_mm);
    } else {
      s.collar_mm = uniform(rng, g.collar_width_mm);
      s.collar_span_deg = 360 * uniform(rng, g.collar_completeness);
    }
    s.collar_start_deg = uniform(rng, 0, 360);
  }
  if (grade == 5) {
    const int pieces = std::uniform_int_distribution<int>(g.min_pieces, g.max_pieces)(rng);
    s.crack_mm = uniform(rng, g.crack_width_mm);
    for (int k = 1; k < pieces; ++k) {
      // Evenly spaced across the middle 1.2 half lengths, so that no piece is a sliver at a tip.
      s.cracks.push_back(-0.6 + 1.2 * k / pieces + uniform(rng, -0.06, 0.06));
      s.crack_tilts_deg.push_back(uniform(rng, -15, 15));
    }
  }
  if (grade == 6) {
    s.remnant_scale_length = uniform(rng, g.remnant_scale);
    s.remnant_scale_width = uniform(rng, g.remnant_scale) + 0.15;
    s.remnant_dx_mm = uniform(rng, -0.4, 0.4);
    s.remnant_dy_mm = uniform(rng, -0.2, 0.2);
    s.kernel_fraction = uniform(rng, g.remnant_level);
    s.kernel_edge_mm = uniform(rng, 0.03, 0.05);  // dispersing: a soft edge, merging into the gel
    s.gel_edge_mm = uniform(rng, 0.04, 0.07);
    const int lobes = std::uniform_int_distribution<int>(2, 3)(rng);
    for (int k = 0; k < lobes; ++k)
      s.lobes.push_back({uniform(rng, -0.25, 0.25) * s.length_mm, uniform(rng, -0.4, 0.4) * s.width_mm,
                         uniform(rng, 0.25, 0.35) * s.length_mm + 0.8 * s.collar_mm,
                         uniform(rng, 0.3, 0.45) * s.width_mm + 0.8 * s.collar_mm, uniform(rng, -40, 40)});
  }
  if (grade == 7) {
    s.gel_level *= uniform(rng, 0.75, 0.9);
    s.gel_texture = uniform(rng, 0.08, 0.14);
    s.gel_edge_mm = uniform(rng, 0.15, 0.30);  // a diffuse cloud
    const int lobes = std::uniform_int_distribution<int>(3, 5)(rng);
    for (int k = 0; k < lobes; ++k) {
      const double reach = uniform(rng, g.cloud_radius_mm);
      s.lobes.push_back({uniform(rng, -0.25, 0.25) * s.length_mm, uniform(rng, -0.3, 0.3) * s.width_mm,
                         uniform(rng, 0.3, 0.4) * s.length_mm + 0.5 * reach,
                         0.4 * s.width_mm + uniform(rng, 0.6, 0.9) * reach, uniform(rng, -30, 30)});
    }
  }
  return s;
}

double grain_reach_mm(const GrainSpec& s) {
  double reach = 0.5 * s.length_mm + s.collar_mm;
  for (const auto& l : s.lobes)
    reach = std::max(reach, std::hypot(l.dx_mm, l.dy_mm) + std::max(l.half_length_mm, l.half_width_mm));
  return reach + 4 * std::max(s.gel_edge_mm, s.kernel_edge_mm) + 0.1;
}

std::vector<cv::Point2d> superellipse_outline(cv::Point2d centre, double a, double b, double angle_deg,
                                              double start_deg, double span_deg) {
  const int steps = std::max(8, static_cast<int>(std::ceil(std::abs(span_deg) * 2)));
  const bool closed = span_deg >= 360;
  const double c = std::cos(angle_deg * kDegree), n = std::sin(angle_deg * kDegree), p = 2 / kRiceExponent;
  std::vector<cv::Point2d> points;
  for (int k = 0; k < steps + (closed ? 0 : 1); ++k) {
    const double t = (start_deg + span_deg * k / steps) * kDegree;
    const double x = a * signed_power(std::cos(t), p), y = b * signed_power(std::sin(t), p);
    points.emplace_back(centre.x + c * x - n * y, centre.y + n * x + c * y);
  }
  return points;
}

double sector_coverage(double a, double b, double start_deg, double span_deg) {
  if (span_deg >= 360) return 1;
  if (span_deg <= 0) return 0;
  const double p = 2 / kRiceExponent;
  auto polar = [&](double t) { return std::atan2(b * signed_power(std::sin(t), p), a * signed_power(std::cos(t), p)); };
  // The polar angle rises monotonically with the parametric one; sum its wrapped increments.
  const int steps = static_cast<int>(std::ceil(span_deg * 20));
  double swept = 0, previous = polar(start_deg * kDegree);
  for (int k = 1; k <= steps; ++k) {
    const double now = polar((start_deg + span_deg * k / steps) * kDegree);
    swept += std::remainder(now - previous, 2 * std::numbers::pi);
    previous = now;
  }
  return std::clamp(swept / (2 * std::numbers::pi), 0.0, 1.0);
}

GrainLayers draw_grain(const GrainSpec& s, double mm_per_px) {
  const double px = 1 / mm_per_px;
  const int half = static_cast<int>(std::ceil(grain_reach_mm(s) * px));
  GrainLayers L;
  L.origin = {static_cast<int>(std::lround(s.centre_px.x)) - half, static_cast<int>(std::lround(s.centre_px.y)) - half};
  const cv::Size size(2 * half + 1, 2 * half + 1);
  const cv::Point2d c = s.centre_px - cv::Point2d(L.origin);
  L.kernel = cv::Mat::zeros(size, CV_8U);
  L.gel = cv::Mat::zeros(size, CV_8U);
  const double a = 0.5 * s.length_mm * px, b = 0.5 * s.width_mm * px;

  // The gel: the collar (a band beyond the kernel outline, or its sector), then any lobes.
  if (s.collar_mm > 0) {
    const double A = a + s.collar_mm * px, B = b + s.collar_mm * px;
    if (s.collar_span_deg >= 360) {
      fill_polygon(L.gel, superellipse_outline(c, A, B, s.angle_deg), 255);
    } else {
      std::vector<cv::Point2d> sector{c};
      const auto arc = superellipse_outline(c, A, B, s.angle_deg, s.collar_start_deg, s.collar_span_deg);
      sector.insert(sector.end(), arc.begin(), arc.end());
      fill_polygon(L.gel, sector, 255);
    }
  }
  for (const auto& l : s.lobes) {
    const cv::Point2d at = c + grain_offset(s, l.dx_mm, l.dy_mm, px);
    const cv::Size axes(static_cast<int>(std::lround(l.half_length_mm * px * kSubpixel)),
                        static_cast<int>(std::lround(l.half_width_mm * px * kSubpixel)));
    cv::ellipse(L.gel, fixed_point(at), axes, s.angle_deg + l.angle_deg, 0, 360, cv::Scalar(255), cv::FILLED,
                cv::LINE_8, kShift);
  }

  // The kernel: intact, split by gel-filled cracks (grade 5), a remnant (grade 6) or gone (grade 7).
  if (s.grade == 6) {
    const cv::Point2d at = c + grain_offset(s, s.remnant_dx_mm, s.remnant_dy_mm, px);
    fill_polygon(L.kernel, superellipse_outline(at, a * s.remnant_scale_length, b * s.remnant_scale_width, s.angle_deg),
                 255);
  } else if (s.grade != 7) {
    fill_polygon(L.kernel, superellipse_outline(c, a, b, s.angle_deg), 255);
    const int crack = std::max(1, static_cast<int>(std::lround(s.crack_mm * px)));
    for (std::size_t k = 0; k < s.cracks.size(); ++k) {
      const cv::Point2d mid = c + grain_offset(s, s.cracks[k] * 0.5 * s.length_mm, 0, px);
      const double t = (s.angle_deg + 90 + s.crack_tilts_deg[k]) * kDegree;
      const cv::Point2d along(std::cos(t) * 2 * b, std::sin(t) * 2 * b);
      cv::line(L.kernel, fixed_point(mid - along), fixed_point(mid + along), cv::Scalar(0), crack, cv::LINE_8, kShift);
    }
  }

  // The gel's grey level: a low-frequency texture (0.4 mm blobs); around a dispersing remnant the gel
  // is brighter, fading over about 0.3 mm, so that kernel and collar merge.
  L.gel_level = low_frequency_noise(size, 0.4 * px, s.texture_seed);
  L.gel_level = s.gel_level * (1 + s.gel_texture * L.gel_level);
  if (s.grade == 6) {
    cv::Mat halo;
    L.kernel.convertTo(halo, CV_32F, 1.0 / 255);
    cv::GaussianBlur(halo, halo, cv::Size(), 0.3 * px);
    L.gel_level += halo * (0.25 * (s.kernel_fraction * s.kernel_level - s.gel_level));
  }
  return L;
}

GrainTruth grain_truth(const GrainSpec& s, const GrainLayers& L, double mm_per_px, double dish_level) {
  GrainTruth t;
  const double pixel_area = mm_per_px * mm_per_px;
  cv::Mat gel_only;
  cv::bitwise_and(L.gel, ~L.kernel, gel_only);
  t.kernel_area_mm2 = cv::countNonZero(L.kernel) * pixel_area;
  t.gel_area_mm2 = cv::countNonZero(gel_only) * pixel_area;
  t.gel_kernel_ratio = t.kernel_area_mm2 > 0 ? t.gel_area_mm2 / t.kernel_area_mm2 : std::nan("");
  if (s.grade == 7 || s.grade == 6) {
    t.collar_completeness = 1;
  } else if (s.collar_mm > 0) {
    const double px = 1 / mm_per_px;
    t.collar_completeness =
        sector_coverage(0.5 * s.length_mm * px + s.collar_mm * px, 0.5 * s.width_mm * px + s.collar_mm * px,
                        s.collar_start_deg, s.collar_span_deg);
  }
  t.kernel_pieces = s.grade == 7 ? 0 : static_cast<int>(s.cracks.size()) + 1;
  const double kernel_mass = t.kernel_area_mm2 / pixel_area * (s.kernel_fraction * s.kernel_level - dish_level);
  const int gel_pixels = cv::countNonZero(gel_only);
  const double gel_mass = gel_pixels > 0 ? (cv::mean(L.gel_level, gel_only)[0] - dish_level) * gel_pixels : 0.0;
  t.kernel_share = kernel_mass / (kernel_mass + gel_mass);
  return t;
}

}  // namespace suite::rice
