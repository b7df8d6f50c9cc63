#pragma once
// Scale calibration from a reference ball of known diameter (docs/methods/carving.md, "Calibration"): the
// ball's silhouette in one image gives its centre and radius in pixels, hence pixels per mm at the
// ball; with the focal length in pixels also the distance from the camera centre to the ball.
//
// The radius comes from a least-squares circle fit to the silhouette's outline, taken as the
// midpoints of the pixel edges between seed and background pixels (the "crack" points, which lie
// within half a pixel of the true outline on both sides of it, so the fit has no half-pixel bias):
// an algebraic (Kasa) fit started, a geometric Gauss-Newton fit finished. A ball seen by a pinhole
// camera on its optical axis has a circular silhouette of radius r = f tan(asin(R / d)) for ball
// radius R at distance d, so d = R / sin(atan(r / f)). Off the axis the silhouette is an ellipse
// and the fitted radius a mean of its semi-axes: keep the ball near the image centre.
#include <limits>
#include <opencv2/core.hpp>

#include "carving/image/mask.hpp"

namespace suite::carving {

struct BallCalibration {
  double px_per_mm = 0;  // radius_px / (diameter / 2): the silhouette's scale at the ball
  double radius_px = 0;
  double centre_x = 0;  // px, pixel centres at integer coordinates
  double centre_y = 0;
  double distance_mm = std::numeric_limits<double>::quiet_NaN();  // camera centre to ball centre; NaN without focal
  double fit_rms_px = 0;  // rms distance of the outline points from the fitted circle
  int outline_points = 0;
};

// The ball is the largest silhouette of the mask (other specks are ignored); it must not touch the
// image border. diameter_mm > 0; focal_px > 0 or NaN (no distance). Throws InputError otherwise,
// or when the mask holds no silhouette.
BallCalibration calibrate_ball(const Mask& mask, double diameter_mm,
                               double focal_px = std::numeric_limits<double>::quiet_NaN());

// The same for an 8-bit single-channel image, non-zero = ball.
BallCalibration calibrate_ball(const cv::Mat& mask, double diameter_mm,
                               double focal_px = std::numeric_limits<double>::quiet_NaN());

}  // namespace suite::carving
