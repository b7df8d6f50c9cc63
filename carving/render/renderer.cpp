// Ray casting of analytic shapes into colour images and exact masks (see renderer.hpp).
#include "carving/render/renderer.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "core/errors.hpp"

namespace suite::carving {

namespace {

// The rays of one view: ray(u, v) gives an origin and a unit direction for pixel coordinates (u, v).
class RayGenerator {
 public:
  RayGenerator(const Projection& P, const BoundingSphere& bounds) : bounds_(bounds) {
    const double scale = P.norm();
    if (!(scale > 0) || !P.allFinite())
      throw InputError("render: the projection matrix is zero or not finite; give a 3x4 matrix P = K [R | t]");
    const Eigen::Matrix3d M = P.leftCols<3>();
    if (M.row(2).norm() <= 1e-12 * scale) {
      if (std::abs(P(2, 3)) <= 1e-12 * scale)
        throw InputError("render: the projection's last row is zero; a parallel projection needs (0, 0, 0, k), k != 0");
      parallel_ = true;
      A_ = P.topLeftCorner<2, 3>() / P(2, 3);
      b_ = P.block<2, 1>(0, 3) / P(2, 3);
      const Eigen::Vector3d d = A_.row(0).transpose().cross(A_.row(1).transpose());
      if (!(d.norm() > 1e-12 * A_.norm() * A_.norm()))
        throw InputError(
            "render: the parallel projection's first two rows are parallel; its 2x3 block must have rank 2");
      direction_ = d.normalized();
      forward_ = direction_;
      pseudo_inverse_ = A_.transpose() * (A_ * A_.transpose()).inverse();
    } else {
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
      if (!lu.isInvertible())
        throw InputError(
            "render: the projection's left 3x3 block is singular and its last row is not (0, 0, 0, k); "
            "give a pinhole P = K [R | t] or a parallel projection");
      M_inverse_ = lu.inverse();
      centre_ = -M_inverse_ * P.col(3);
      forward_ = M.row(2).transpose().normalized();  // w grows into the scene
    }
    // Camera axes: z = forward, y = image down (M's second row without its z part), x = y x z.
    const Eigen::Vector3d m2 = M.row(1).transpose();
    down_ = (m2 - m2.dot(forward_) * forward_).normalized();
    right_ = down_.cross(forward_);
  }

  // A direction given in camera coordinates, in the world.
  Eigen::Vector3d camera_to_world(const Eigen::Vector3d& v) const {
    return v.x() * right_ + v.y() * down_ + v.z() * forward_;
  }

  // Origin and unit direction of the ray through (u, v); for parallel projection the origin is
  // put a little before the bounding sphere so that first_hit sees the whole line's crossing.
  void ray(double u, double v, Eigen::Vector3d& origin, Eigen::Vector3d& direction) const {
    if (parallel_) {
      const Eigen::Vector3d on_line = pseudo_inverse_ * (Eigen::Vector2d(u, v) - b_);
      direction = direction_;
      origin = on_line + ((bounds_.centre - on_line).dot(direction_) - 2 * bounds_.radius - 1) * direction_;
    } else {
      direction = (M_inverse_ * Eigen::Vector3d(u, v, 1)).normalized();
      origin = centre_;
    }
  }

 private:
  BoundingSphere bounds_;
  bool parallel_ = false;
  Eigen::Matrix<double, 2, 3> A_;
  Eigen::Vector2d b_;
  Eigen::Matrix<double, 3, 2> pseudo_inverse_;
  Eigen::Vector3d direction_, centre_;
  Eigen::Vector3d forward_, down_, right_;
  Eigen::Matrix3d M_inverse_;
};

// True when the ray can reach the bounding sphere: a cheap rejection before first_hit.
bool near_sphere(const BoundingSphere& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const Eigen::Vector3d w = s.centre - o;
  const double along = w.dot(d);
  return (w - along * d).squaredNorm() <= s.radius * s.radius * (1 + 1e-9) && along + s.radius >= 0;
}

void check_options(const View& view, const RenderOptions& o) {
  if (view.width < 1 || view.height < 1)
    throw InputError(fmt::format("render: the view is {} x {} pixels; width and height must be at least 1", view.width,
                                 view.height));
  if (o.supersampling < 1 || o.supersampling > 16)
    throw InputError(fmt::format("render option supersampling = {}; it must lie in 1..16", o.supersampling));
  if (!(o.blur_sigma_px >= 0) || !std::isfinite(o.blur_sigma_px))
    throw InputError(fmt::format("render option blur_sigma_px = {}; it must be >= 0 (0 = no blur)", o.blur_sigma_px));
  if (!(o.noise_sigma >= 0) || !std::isfinite(o.noise_sigma))
    throw InputError(fmt::format("render option noise_sigma = {}; it must be >= 0 (0 = no noise)", o.noise_sigma));
  if (!(o.ambient >= 0 && o.ambient <= 1))
    throw InputError(fmt::format("render option ambient = {}; it must lie in [0, 1]", o.ambient));
  if (!(o.light_direction.norm() > 0) || !o.light_direction.allFinite())
    throw InputError("render option light_direction is zero or not finite; give a direction towards the light");
}

// Standard normal deviates from the fully specified mt19937_64 stream (Box-Muller), so the noise is
// the same with every standard library, unlike std::normal_distribution.
class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) : engine_(seed) {}
  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53;  // (0, 1)
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;          // [0, 1)
    const double r = std::sqrt(-2 * std::log(u1)), phi = 2 * std::numbers::pi * u2;
    spare_ = r * std::sin(phi);
    has_spare_ = true;
    return r * std::cos(phi);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace

RenderedView render(const Shape& shape, const View& view, const RenderOptions& options) {
  check_options(view, options);
  const BoundingSphere bounds = shape.bounding_sphere();
  const RayGenerator rays(view.P, bounds);
  const Eigen::Vector3d light = rays.camera_to_world(options.light_direction).normalized();
  const int s = options.supersampling;
  const cv::Vec3f background(options.background_bgr[0], options.background_bgr[1], options.background_bgr[2]);
  const cv::Vec3f albedo(options.seed_bgr[0], options.seed_bgr[1], options.seed_bgr[2]);

  // Colour of one ray, and whether it hit.
  const auto shade = [&](double u, double v, cv::Vec3f& colour) {
    Eigen::Vector3d o, d;
    rays.ray(u, v, o, d);
    if (!near_sphere(bounds, o, d)) {
      colour = background;
      return false;
    }
    const auto t = shape.first_hit(o, d);
    if (!t) {
      colour = background;
      return false;
    }
    const Eigen::Vector3d n = shape.normal(o + *t * d);
    const double lambert = std::max(0.0, n.dot(light));
    colour = albedo * static_cast<float>(options.ambient + (1 - options.ambient) * lambert);
    return true;
  };

  std::vector<std::uint8_t> mask(static_cast<std::size_t>(view.width) * view.height, 0);
  cv::Mat colour(view.height, view.width, CV_32FC3);
  std::vector<double> offsets(s);
  for (int i = 0; i < s; ++i) offsets[i] = (i + 0.5) / s - 0.5;
  const bool centre_sampled = s % 2 == 1;  // the centre ray is one of the s x s samples
  for (int y = 0; y < view.height; ++y) {
    auto* row = colour.ptr<cv::Vec3f>(y);
    for (int x = 0; x < view.width; ++x) {
      cv::Vec3f sum(0, 0, 0), c;
      for (int j = 0; j < s; ++j)
        for (int i = 0; i < s; ++i) {
          const bool hit = shade(x + offsets[i], y + offsets[j], c);
          sum += c;
          if (centre_sampled && i == s / 2 && j == s / 2) mask[static_cast<std::size_t>(y) * view.width + x] = hit;
        }
      if (!centre_sampled) mask[static_cast<std::size_t>(y) * view.width + x] = shade(x, y, c);
      row[x] = sum / static_cast<float>(s * s);
    }
  }

  if (options.blur_sigma_px > 0) cv::GaussianBlur(colour, colour, cv::Size(0, 0), options.blur_sigma_px);
  if (options.noise_sigma > 0) {
    GaussianNoise noise(options.noise_seed);
    for (int y = 0; y < view.height; ++y) {
      auto* row = colour.ptr<cv::Vec3f>(y);
      for (int x = 0; x < view.width; ++x)
        for (int k = 0; k < 3; ++k) row[x][k] += static_cast<float>(options.noise_sigma * noise.next());
    }
  }
  RenderedView out;
  colour.convertTo(out.image, CV_8UC3);  // rounds and saturates to 0..255
  out.mask = Mask(view.width, view.height, std::move(mask));
  return out;
}

}  // namespace suite::carving
