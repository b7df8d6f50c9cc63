// Reference-ball calibration: circle fit to the silhouette's crack outline (see the header).
#include "carving/calibration/ball.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/errors.hpp"

namespace suite::carving {
namespace {

struct Circle {
  double x = 0, y = 0, r = 0;
};

// Algebraic fit: x^2 + y^2 + D x + E y + F = 0 in the least-squares sense.
Circle fit_kasa(const std::vector<Eigen::Vector2d>& pts) {
  Eigen::MatrixXd A(pts.size(), 3);
  Eigen::VectorXd b(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    A(i, 0) = pts[i].x();
    A(i, 1) = pts[i].y();
    A(i, 2) = 1;
    b(i) = -pts[i].squaredNorm();
  }
  const Eigen::Vector3d c = A.colPivHouseholderQr().solve(b);
  Circle out;
  out.x = -c(0) / 2;
  out.y = -c(1) / 2;
  out.r = std::sqrt(std::max(0.0, out.x * out.x + out.y * out.y - c(2)));
  return out;
}

// Geometric fit: minimise sum (|p - centre| - r)^2 by Gauss-Newton from `start`.
Circle fit_geometric(const std::vector<Eigen::Vector2d>& pts, Circle c) {
  for (int iter = 0; iter < 50; ++iter) {
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (const auto& p : pts) {
      const double dx = p.x() - c.x, dy = p.y() - c.y, rho = std::hypot(dx, dy);
      if (rho == 0) continue;
      const Eigen::Vector3d J(-dx / rho, -dy / rho, -1.0);  // d(rho - r)/d(x, y, r)
      const double res = rho - c.r;
      JtJ += J * J.transpose();
      Jtr += J * res;
    }
    const Eigen::Vector3d step = JtJ.ldlt().solve(-Jtr);
    c.x += step(0);
    c.y += step(1);
    c.r += step(2);
    if (step.norm() < 1e-12) break;
  }
  return c;
}

}  // namespace

BallCalibration calibrate_ball(const cv::Mat& mask, double diameter_mm, double focal_px) {
  if (!(diameter_mm > 0) || !std::isfinite(diameter_mm))
    throw InputError(
        fmt::format("ball calibration: diameter {} mm; give the reference ball's diameter in mm (> 0)", diameter_mm));
  if (!std::isnan(focal_px) && (!(focal_px > 0) || !std::isfinite(focal_px)))
    throw InputError(
        fmt::format("ball calibration: focal length {} px; give a positive focal length in pixels, or "
                    "none for no distance",
                    focal_px));
  if (mask.empty() || mask.type() != CV_8UC1)
    throw InputError(
        fmt::format("ball calibration: the mask is {} x {} of OpenCV type {}; give a non-empty 8-bit "
                    "single-channel mask (non-zero = ball)",
                    mask.cols, mask.rows, mask.type()));

  // The largest outer contour is the ball; redraw it filled, so specks and holes do not matter.
  cv::Mat binary = mask != 0;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(binary, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  if (contours.empty())
    throw InputError("ball calibration: the mask holds no silhouette; segment the image with the ball in view");
  std::size_t best = 0;
  double best_area = -1;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    const double area = cv::contourArea(contours[i]) + static_cast<double>(contours[i].size());  // specks have area 0
    if (area > best_area) {
      best_area = area;
      best = i;
    }
  }
  const cv::Rect box = cv::boundingRect(contours[best]);
  if (box.x == 0 || box.y == 0 || box.x + box.width == mask.cols || box.y + box.height == mask.rows)
    throw InputError(
        fmt::format("ball calibration: the ball's silhouette (box {} x {} px at ({}, {})) touches the "
                    "image border; photograph the whole ball",
                    box.width, box.height, box.x, box.y));
  cv::Mat ball = cv::Mat::zeros(mask.size(), CV_8UC1);
  cv::drawContours(ball, contours, static_cast<int>(best), cv::Scalar(255), cv::FILLED);

  // Crack points: midpoints of the edges between a ball pixel and a background 4-neighbour.
  std::vector<Eigen::Vector2d> pts;
  for (int y = box.y; y < box.y + box.height; ++y)
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (!ball.at<std::uint8_t>(y, x)) continue;
      if (!ball.at<std::uint8_t>(y, x - 1)) pts.emplace_back(x - 0.5, y);
      if (!ball.at<std::uint8_t>(y, x + 1)) pts.emplace_back(x + 0.5, y);
      if (!ball.at<std::uint8_t>(y - 1, x)) pts.emplace_back(x, y - 0.5);
      if (!ball.at<std::uint8_t>(y + 1, x)) pts.emplace_back(x, y + 0.5);
    }
  if (pts.size() < 8)
    throw InputError(
        fmt::format("ball calibration: the ball's silhouette has only {} outline points; the ball must "
                    "span several pixels",
                    pts.size()));

  const Circle c = fit_geometric(pts, fit_kasa(pts));
  double ss = 0;
  for (const auto& p : pts) ss += std::pow(std::hypot(p.x() - c.x, p.y() - c.y) - c.r, 2);

  BallCalibration out;
  out.centre_x = c.x;
  out.centre_y = c.y;
  out.radius_px = c.r;
  out.px_per_mm = c.r / (diameter_mm / 2);
  out.fit_rms_px = std::sqrt(ss / static_cast<double>(pts.size()));
  out.outline_points = static_cast<int>(pts.size());
  if (!std::isnan(focal_px)) out.distance_mm = (diameter_mm / 2) / std::sin(std::atan(c.r / focal_px));
  return out;
}

BallCalibration calibrate_ball(const Mask& mask, double diameter_mm, double focal_px) {
  cv::Mat m(mask.height(), mask.width(), CV_8UC1);
  for (int y = 0; y < mask.height(); ++y)
    for (int x = 0; x < mask.width(); ++x) m.at<std::uint8_t>(y, x) = mask.at(x, y) ? 255 : 0;
  return calibrate_ball(m, diameter_mm, focal_px);
}

}  // namespace suite::carving
