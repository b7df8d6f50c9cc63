#pragma once
// Camera intrinsics from photographs of a flat chessboard (docs/methods/carving.md, "OpenCV chessboard
// calibration for K when given"): the inner corners are found in every image
// (cv::findChessboardCorners), refined to sub-pixel accuracy (cv::cornerSubPix) and handed with the
// board's known geometry to cv::calibrateCamera (Zhang's method with lens distortion).
#include <opencv2/core.hpp>
#include <vector>

#include "carving/camera/camera.hpp"

namespace suite::carving {

struct ChessboardCalibration {
  Intrinsics intrinsics;           // focal_px = (fx + fy) / 2, and the principal point
  double fx = 0, fy = 0;           // px
  std::vector<double> distortion;  // OpenCV order: k1, k2, p1, p2, k3
  double rms_px = 0;               // rms reprojection error over all corners
  std::vector<double> per_image_rms_px;
  int images = 0;
};

struct ChessboardOptions {
  int subpix_half_window = 5;  // cv::cornerSubPix search window half size (px); about a third of a square
  int calibrate_flags = 0;     // cv::calibrateCamera flags, e.g. cv::CALIB_FIX_K3 for an ordinary lens
};

// images: at least 3 photographs (8-bit grey or BGR, one size) of a board with `inner_corners`
// (columns x rows of inner corners, each >= 2) squares of `square_mm` mm, in varied poses (tilted
// boards constrain the focal length; boards parallel to the image do not). Throws InputError naming
// the image whose corners were not found, or a bad argument.
ChessboardCalibration calibrate_chessboard(const std::vector<cv::Mat>& images, cv::Size inner_corners, double square_mm,
                                           const ChessboardOptions& options = {});

}  // namespace suite::carving
