// Chessboard calibration of the camera intrinsics with OpenCV (see the header).
#include "carving/calibration/chessboard.hpp"

#include <fmt/format.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "core/errors.hpp"

namespace suite::carving {

ChessboardCalibration calibrate_chessboard(const std::vector<cv::Mat>& images, cv::Size inner_corners, double square_mm,
                                           const ChessboardOptions& options) {
  if (images.size() < 3)
    throw InputError(
        fmt::format("chessboard calibration: {} images; give at least 3 photographs of the board in "
                    "different tilted poses",
                    images.size()));
  if (inner_corners.width < 2 || inner_corners.height < 2)
    throw InputError(
        fmt::format("chessboard calibration: pattern {} x {} inner corners; give the board's inner "
                    "corners per row and per column (each >= 2; a board of 9 x 7 squares has 8 x 6)",
                    inner_corners.width, inner_corners.height));
  if (!(square_mm > 0) || !std::isfinite(square_mm))
    throw InputError(
        fmt::format("chessboard calibration: square size {} mm; give the side of one square in mm (> 0)", square_mm));
  if (options.subpix_half_window < 1)
    throw InputError(
        fmt::format("chessboard calibration: sub-pixel half window {} px; give >= 1", options.subpix_half_window));

  // The board's corners in its own plane (z = 0), row by row as OpenCV reports them.
  std::vector<cv::Point3f> board;
  for (int r = 0; r < inner_corners.height; ++r)
    for (int c = 0; c < inner_corners.width; ++c)
      board.emplace_back(static_cast<float>(c * square_mm), static_cast<float>(r * square_mm), 0.0F);

  const cv::Size size = images[0].size();
  std::vector<std::vector<cv::Point3f>> object_points;
  std::vector<std::vector<cv::Point2f>> image_points;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const cv::Mat& img = images[i];
    if (img.empty() || img.depth() != CV_8U || (img.channels() != 1 && img.channels() != 3))
      throw InputError(
          fmt::format("chessboard calibration: image {} is empty or not 8-bit grey or BGR "
                      "({} x {}, {} channels)",
                      i, img.cols, img.rows, img.channels()));
    if (img.size() != size)
      throw InputError(
          fmt::format("chessboard calibration: image {} is {} x {} px but image 0 is {} x {} px; use "
                      "one camera setting for all images",
                      i, img.cols, img.rows, size.width, size.height));
    cv::Mat grey;
    if (img.channels() == 3)
      cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
    else
      grey = img;
    std::vector<cv::Point2f> corners;
    const bool found = cv::findChessboardCorners(grey, inner_corners, corners,
                                                 cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
    if (!found)
      throw InputError(
          fmt::format("chessboard calibration: image {} shows no chessboard of {} x {} inner corners; "
                      "check the pattern size and that the whole board is in view and sharp",
                      i, inner_corners.width, inner_corners.height));
    const cv::Size window(options.subpix_half_window, options.subpix_half_window);
    cv::cornerSubPix(grey, corners, window, cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
    object_points.push_back(board);
    image_points.push_back(std::move(corners));
  }

  cv::Mat K, dist;
  std::vector<cv::Mat> rvecs, tvecs;
  ChessboardCalibration out;
  out.rms_px = cv::calibrateCamera(object_points, image_points, size, K, dist, rvecs, tvecs, options.calibrate_flags);
  out.fx = K.at<double>(0, 0);
  out.fy = K.at<double>(1, 1);
  out.intrinsics = Intrinsics{(out.fx + out.fy) / 2, K.at<double>(0, 2), K.at<double>(1, 2)};
  out.distortion.assign(dist.begin<double>(), dist.end<double>());
  out.images = static_cast<int>(images.size());
  for (std::size_t i = 0; i < images.size(); ++i) {
    std::vector<cv::Point2f> projected;
    cv::projectPoints(object_points[i], rvecs[i], tvecs[i], K, dist, projected);
    double ss = 0;
    for (std::size_t j = 0; j < projected.size(); ++j) {
      const cv::Point2f d = projected[j] - image_points[i][j];
      ss += d.dot(d);
    }
    out.per_image_rms_px.push_back(std::sqrt(ss / static_cast<double>(projected.size())));
  }
  return out;
}

}  // namespace suite::carving
