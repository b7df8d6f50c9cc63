// Calibration: reference ball (scale and distance), turntable axis and crop-to-frame registration
// on rendered silhouettes, chessboard intrinsics on rendered boards, and the real K-State wheat
// grain carved from its 36 photographs alone (own segmentation, own axis estimate).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "carving/calibration/ball.hpp"
#include "carving/calibration/chessboard.hpp"
#include "carving/calibration/turntable_axis.hpp"
#include "carving/hull/carver.hpp"
#include "carving/io/carve_input.hpp"
#include "core/errors.hpp"

namespace suite::carving {
namespace {

constexpr double kPi = std::numbers::pi;
const std::filesystem::path kWheatDir = SUITE_DATA_DIR "/kstate_wheat_36view";

// ---------------------------------------------------------------------------------------------
// Rendering helpers

// A disc of radius r px about (cx, cy): pixel (x, y) is set when its centre lies in the disc.
Mask disc_mask(int width, int height, double cx, double cy, double r) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) px[static_cast<std::size_t>(y) * width + x] = std::hypot(x - cx, y - cy) <= r;
  return Mask(width, height, std::move(px));
}

// An ellipsoid (X - c)^T A (X - c) <= 1, with A = Q diag(1 / a_i^2) Q^T.
struct Ellipsoid {
  Eigen::Vector3d centre;
  Eigen::Matrix3d A;
  double volume;
};

Ellipsoid make_ellipsoid(const Eigen::Vector3d& semi_axes, const Eigen::Matrix3d& Q, const Eigen::Vector3d& centre) {
  const Eigen::Matrix3d D = semi_axes.cwiseInverse().cwiseAbs2().asDiagonal();
  return {centre, Q * D * Q.transpose(), 4.0 / 3.0 * kPi * semi_axes.prod()};
}

// Exact pinhole silhouette: pixel (x, y) is set when the ray from the camera centre through the
// pixel centre meets the ellipsoid (real roots of the quadratic along the ray, in front).
Mask render_pinhole(const Ellipsoid& e, const View& view) {
  const Eigen::Matrix3d M = view.P.leftCols<3>();
  const Eigen::Matrix3d Minv = M.inverse();
  const Eigen::Vector3d C = -Minv * view.P.col(3);
  const Eigen::Vector3d oc = C - e.centre;
  const double c0 = oc.dot(e.A * oc) - 1;
  std::vector<std::uint8_t> px(static_cast<std::size_t>(view.width) * view.height);
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const Eigen::Vector3d d = Minv * Eigen::Vector3d(x, y, 1);
      const double a = d.dot(e.A * d), b = d.dot(e.A * oc);
      px[static_cast<std::size_t>(y) * view.width + x] = (b * b - a * c0 >= 0 && b < 0) ? 1 : 0;
    }
  return Mask(view.width, view.height, std::move(px));
}

// A wheat-like ellipsoid (7.2 x 3.6 x 2.9 mm, docs/methods/carving.md) tilted and placed off the axis.
Ellipsoid off_axis_grain() {
  const Eigen::Matrix3d Q =
      (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(0.15, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  return make_ellipsoid({3.6, 1.8, 1.45}, Q, {0.8, 0.25, -0.55});
}

std::vector<double> turn_angles(int views, int sense) {
  std::vector<double> a;
  for (int i = 0; i < views; ++i) a.push_back(sense * 2 * kPi * i / views);
  return a;
}

// ---------------------------------------------------------------------------------------------
// Reference ball

// A digitised disc of radius ~46 px gives ~370 crack points, each within half a pixel of the
// circle and unbiased on average; the fitted radius is good to about 0.01 px, so 0.1% of the
// scale (0.05 px) is a safe bound that still catches a half-pixel bias (1%).
constexpr double kBallScaleTolerance = 1e-3;
// Centre: the digitised outline is not symmetric about an off-grid centre, which moves the fitted
// centre by a few hundredths of a pixel (0.02-0.035 px seen here); 0.05 px bounds that.
constexpr double kBallCentreTolerancePx = 0.05;

TEST(BallCalibration, DiscGivesPixelsPerMm) {
  const double px_per_mm = 23.47, diameter = 3.95;  // the dissertation's ceramic ball at the K-State scale
  const Mask m = disc_mask(300, 240, 150.3, 120.7, px_per_mm * diameter / 2);
  const BallCalibration b = calibrate_ball(m, diameter);
  RecordProperty("ball", fmt::format("px/mm error {:.2e}, centre error ({:.4f}, {:.4f}) px, rms {:.3f} px, {} points",
                                     b.px_per_mm / px_per_mm - 1, b.centre_x - 150.3, b.centre_y - 120.7, b.fit_rms_px,
                                     b.outline_points));
  EXPECT_NEAR(b.px_per_mm / px_per_mm, 1.0, kBallScaleTolerance);
  EXPECT_NEAR(b.centre_x, 150.3, kBallCentreTolerancePx);
  EXPECT_NEAR(b.centre_y, 120.7, kBallCentreTolerancePx);
  EXPECT_LT(b.fit_rms_px, 0.5);  // crack points lie within half a pixel of the outline
  EXPECT_TRUE(std::isnan(b.distance_mm));
}

// The distance follows d = R / sin(atan(r / f)), so its relative error is that of the radius
// (times 1 + small terms): 0.1% from the fit; 0.5% leaves room for the digitisation of a
// perspective silhouette and still catches a wrong formula (using r = f R / d is off by
// R^2 / 2 d^2 only, but tan vs sin mix-ups or a half-pixel bias are off by 1% or more).
constexpr double kBallDistanceTolerance = 5e-3;

TEST(BallCalibration, PinholeSphereGivesDistance) {
  const double f = 2173.9, d = 93.1, R = 3.95 / 2;
  const double cx = 160.37, cy = 120.61;  // the ball on the optical axis, off the pixel grid
  std::vector<std::uint8_t> px(320 * 240);
  for (int y = 0; y < 240; ++y)
    for (int x = 0; x < 320; ++x) {
      // Distance from the ball centre (0, 0, d) to the ray through the pixel centre.
      const Eigen::Vector3d dir = Eigen::Vector3d((x - cx) / f, (y - cy) / f, 1).normalized();
      const double along = d * dir.z();
      px[static_cast<std::size_t>(y) * 320 + x] = (d * d - along * along <= R * R) ? 1 : 0;
    }
  const BallCalibration b = calibrate_ball(Mask(320, 240, std::move(px)), 2 * R, f);
  RecordProperty("ball_pinhole",
                 fmt::format("radius error {:.2e}, distance error {:.2e}",
                             b.radius_px / (f * std::tan(std::asin(R / d))) - 1, b.distance_mm / d - 1));
  EXPECT_NEAR(b.radius_px / (f * std::tan(std::asin(R / d))), 1.0, kBallScaleTolerance);
  EXPECT_NEAR(b.distance_mm / d, 1.0, kBallDistanceTolerance);
  EXPECT_NEAR(b.centre_x, cx, kBallCentreTolerancePx);
  EXPECT_NEAR(b.centre_y, cy, kBallCentreTolerancePx);
}

TEST(BallCalibration, RejectsBadInput) {
  const Mask m = disc_mask(100, 100, 50, 50, 20);
  EXPECT_THROW(calibrate_ball(m, 0.0), InputError);
  EXPECT_THROW(calibrate_ball(m, 4.0, -5.0), InputError);
  EXPECT_THROW(calibrate_ball(Mask(50, 50, std::vector<std::uint8_t>(2500, 0)), 4.0), InputError);
  EXPECT_THROW(calibrate_ball(disc_mask(100, 100, 10, 50, 20), 4.0), InputError);  // cut by the border
}

// ---------------------------------------------------------------------------------------------
// Turntable axis

// The centroid model is exact for parallel views; for pinhole views the mirror symmetry of
// opposite views breaks at order (offset / distance)^2, a few hundredths of a pixel here, and the
// pixel grid adds noise that averages over 36 views. Half a pixel is the bound the carving needs:
// on the real grain a 0.5 px error in the column costs 1% of the volume.
constexpr double kAxisTolerancePx = 0.5;

TEST(TurntableAxis, OffAxisEllipsoidUnderPinholeTurntable) {
  Turntable rig;
  rig.K = Intrinsics{2173.9, 201.3, 152.6};  // the axis column is 201.3
  rig.distance_mm = 93.1;
  rig.views = 36;
  rig.step = 2 * kPi / 36;
  rig.width = 400;
  rig.height = 300;
  const Ellipsoid e = off_axis_grain();
  std::vector<Mask> masks;
  for (const View& v : rig.all_views()) masks.push_back(render_pinhole(e, v));
  const AxisEstimate est = estimate_axis(masks, turn_angles(36, 1));
  RecordProperty("axis", fmt::format("column error {:.4f} px, stderr {:.4f}, residual {:.4f}, orbit {:.2f} px",
                                     est.column - 201.3, est.column_stderr_px, est.residual_px, est.orbit_radius_px));
  EXPECT_NEAR(est.column, 201.3, kAxisTolerancePx);
  EXPECT_LT(est.column_stderr_px, kAxisTolerancePx);
  // The centroid swings by about the offset from the axis, 0.8 mm x 23.3 px/mm ~ 19 px, more or
  // less what the ellipse's tilt adds: a loose check that the swing is seen.
  EXPECT_GT(est.orbit_radius_px, 5.0);
  EXPECT_LT(est.orbit_radius_px, 40.0);
  EXPECT_EQ(est.harmonics, 5);  // k = 1, 3, 5, 7, 9 from 36 views
  // The grain's centre is 0.25 mm below the origin (y down), so the silhouettes sit lower than
  // the origin's row 152.6 by ~6 px.
  EXPECT_GT(est.row, 152.6);
  EXPECT_LT(est.row, 152.6 + 12);
}

TEST(TurntableAxis, FewViewsAndErrors) {
  // Half a turn in 4 views (0, 45, 90, 135 degrees) of a parallel rig: the first harmonic only.
  ParallelTurntable rig;
  rig.scale_px_per_mm = 20;
  rig.cx = 100.4;
  rig.cy = 80;
  rig.views = 4;
  rig.step = kPi / 4;
  rig.width = 200;
  rig.height = 160;
  const Ellipsoid e = make_ellipsoid({1.5, 1.5, 1.5}, Eigen::Matrix3d::Identity(), {1.0, 0, 0.5});  // a ball
  std::vector<Mask> masks;
  for (const View& v : rig.all_views()) {
    // A parallel view of a ball is a disc about the projected centre.
    const Eigen::Vector2d c = project(v.P, e.centre);
    masks.push_back(disc_mask(v.width, v.height, c.x(), c.y(), 1.5 * 20));
  }
  const std::vector<double> half_turn = {0, kPi / 4, kPi / 2, 3 * kPi / 4};
  const AxisEstimate h = estimate_axis(masks, half_turn);
  EXPECT_EQ(h.harmonics, 1);
  EXPECT_NEAR(h.column, 100.4, 0.05);  // a digitised disc's centroid is its centre to ~0.01 px
  EXPECT_NEAR(h.orbit_radius_px, std::hypot(1.0, 0.5) * 20, 0.1);

  EXPECT_THROW(estimate_axis(masks, {0, 1}), InputError);                 // counts differ
  EXPECT_THROW(estimate_axis({masks[0], masks[1]}, {0, 1}), InputError);  // too few views
  EXPECT_THROW(estimate_axis(masks, {0, 1e-9, 2e-9, 3e-9}), InputError);  // angles fix nothing
  std::vector<Mask> with_empty = masks;
  with_empty[2] = Mask(200, 160, std::vector<std::uint8_t>(200 * 160, 0));
  EXPECT_THROW(estimate_axis(with_empty, half_turn), InputError);
}

TEST(TurntableAxis, ShiftAndPlaceViews) {
  Turntable rig;
  rig.K = Intrinsics{1811.594, 100, 100};
  rig.distance_mm = 93.1;
  rig.views = 4;
  rig.step = kPi / 2;
  rig.width = rig.height = 200;
  const std::vector<View> crops = rig.all_views();
  const Eigen::Vector3d X(0.7, -0.4, 1.1);
  const auto shifted = shift_views(crops, 201.5, 122.5, 640, 277);
  ASSERT_EQ(shifted.size(), 4U);
  EXPECT_EQ(shifted[1].width, 640);
  EXPECT_EQ(shifted[1].height, 277);
  const Eigen::Vector2d a = project(crops[1].P, X), b = project(shifted[1].P, X);
  EXPECT_NEAR(b.x() - a.x(), 201.5, 1e-9);
  EXPECT_NEAR(b.y() - a.y(), 122.5, 1e-9);
  // Scaled and mirrored: frame = (-1.2 u + x0, 1.2 v + y0).
  const auto placed = place_views(crops, CropPlacement{441.5, 122.5, 1.2, true}, 640, 277);
  const Eigen::Vector2d c = project(placed[1].P, X);
  EXPECT_NEAR(c.x(), -1.2 * a.x() + 441.5, 1e-9);
  EXPECT_NEAR(c.y(), 1.2 * a.y() + 122.5, 1e-9);
  EXPECT_THROW(place_views(crops, CropPlacement{0, 0, 0.0, false}, 640, 277), InputError);
  EXPECT_THROW(shift_views(crops, 0, 0, 0, 277), InputError);
}

// Registration of a crop calibration to frames that are 1.2x larger, with the axis elsewhere and
// the turntable turning the other way: the sense must be found, the placement recovered to the
// axis tolerance, and the carved volume equal to the one with the true frame cameras.
// The two volumes differ only through the column error (<= 0.5 px of a ~70 px grain) and the
// origin row (nearly irrelevant): 1% bounds both.
constexpr double kRegisteredVolumeTolerance = 0.01;

TEST(TurntableAxis, RegisterCropsToMirroredScaledFrames) {
  const double scale = 1.2, f_crop = 1811.594, d = 93.1;
  Turntable crop_rig;
  crop_rig.K = Intrinsics{f_crop, 100, 100};
  crop_rig.distance_mm = d;
  crop_rig.views = 36;
  crop_rig.step = 2 * kPi / 36;
  crop_rig.width = crop_rig.height = 200;
  Turntable frame_rig = crop_rig;
  frame_rig.K = Intrinsics{scale * f_crop, 321.5, 138.5};  // the whole grain in view
  frame_rig.step = -crop_rig.step;                         // the frames turn the other way
  frame_rig.width = 640;
  frame_rig.height = 277;
  const Ellipsoid e = off_axis_grain();
  std::vector<Mask> frames;
  const std::vector<View> truth = frame_rig.all_views();
  for (const View& v : truth) frames.push_back(render_pinhole(e, v));

  RegistrationOptions opt;
  opt.scale = scale;
  opt.grid = VoxelGrid::cube({0, 0, 0}, 10, 64);
  const Registration reg = register_to_frames(frames, crop_rig.all_views(), turn_angles(36, 1), opt);
  EXPECT_TRUE(reg.placement.mirrored);
  EXPECT_GT(reg.volume_mm3, reg.other_sense_volume_mm3);
  EXPECT_NEAR(reg.column, 321.5, kAxisTolerancePx);
  EXPECT_NEAR(reg.placement.x0, 321.5 + scale * 100, kAxisTolerancePx);
  EXPECT_NEAR(reg.crop_axis_column, 100, 1e-9);
  ASSERT_EQ(reg.views.size(), 36U);

  const VoxelGrid grid = VoxelGrid::cube({0, 0, 0}, 10, 100);
  const double v_reg = carve(reg.views, frames, grid).volume_mm3;
  const double v_true = carve(truth, frames, grid).volume_mm3;
  RecordProperty("registration",
                 fmt::format("column error {:.4f} px, volume ratio {:.5f}, sense volumes {:.3f} / {:.3f}",
                             reg.column - 321.5, v_reg / v_true, reg.volume_mm3, reg.other_sense_volume_mm3));
  EXPECT_NEAR(v_reg / v_true, 1.0, kRegisteredVolumeTolerance);
  EXPECT_NEAR(v_true / e.volume, 1.0, 0.03);  // a 0.1 mm grid on a ~39 mm^3 ellipsoid: a sanity check

  RegistrationOptions no_grid;
  no_grid.scale = scale;
  EXPECT_THROW(register_to_frames(frames, crop_rig.all_views(), turn_angles(36, 1), no_grid), InputError);
  std::vector<View> bent = crop_rig.all_views();
  bent[3].P(0, 3) += 50 * bent[3].P(2, 3);  // view 3 sees the origin 50 px off
  EXPECT_THROW(register_to_frames(frames, bent, turn_angles(36, 1), opt), InputError);
}

// ---------------------------------------------------------------------------------------------
// Chessboard

// Renders a board of (cols + 1) x (rows + 1) squares (inner corners cols x rows) seen by a pinhole
// camera with no distortion, black squares filled at their projected corners (anti-aliased,
// 1/16 px vertex precision), on a white background.
cv::Mat render_board(const cv::Size& inner, double square, const cv::Matx33d& K, const cv::Vec3d& rvec,
                     const cv::Vec3d& tvec, const cv::Size& image) {
  cv::Mat img(image, CV_8UC1, cv::Scalar(255));
  const double x_offset = -(inner.width + 1) * square / 2, y_offset = -(inner.height + 1) * square / 2;
  for (int j = 0; j <= inner.height; ++j)
    for (int i = 0; i <= inner.width; ++i) {
      if ((i + j) % 2 != 0) continue;
      std::vector<cv::Point3d> corners = {{x_offset + i * square, y_offset + j * square, 0},
                                          {x_offset + (i + 1) * square, y_offset + j * square, 0},
                                          {x_offset + (i + 1) * square, y_offset + (j + 1) * square, 0},
                                          {x_offset + i * square, y_offset + (j + 1) * square, 0}};
      std::vector<cv::Point2d> projected;
      cv::projectPoints(corners, rvec, tvec, K, cv::noArray(), projected);
      std::vector<cv::Point> poly;
      for (const auto& p : projected) poly.emplace_back(cvRound(p.x * 16), cvRound(p.y * 16));
      cv::fillConvexPoly(img, poly, cv::Scalar(0), cv::LINE_AA, 4);
    }
  return img;
}

// Zhang's method on 8 tilted views of 48 corners located to ~0.05 px recovers f to ~0.1-0.3%
// (the rendering is exact up to anti-aliasing); 1% is the accuracy the carving needs from K
// (volume ~ f^-3 at fixed distance only through the perspective terms, and through px/mm when the
// distance comes from a ball).
constexpr double kFocalTolerance = 0.01;
// Principal point: a few pixels, since it trades off against the board poses.
constexpr double kPrincipalPointTolerancePx = 3.0;

TEST(Chessboard, RecoversFocalLength) {
  const cv::Size inner(8, 6), image(640, 480);
  const double square = 10, f = 900;
  const cv::Matx33d K(f, 0, 320.5, 0, f, 240.5, 0, 0, 1);
  // Tilts of 15-25 degrees about varied axes, boards spread over the image (corners included) so
  // that distortion and principal point are constrained too.
  const std::vector<cv::Vec3d> rotations = {{0.35, 0.0, 0.0},  {-0.35, 0.1, 0.0}, {0.0, 0.4, 0.1},
                                            {0.1, -0.4, -0.1}, {0.3, 0.3, 0.3},   {-0.3, -0.25, 0.5},
                                            {0.2, -0.2, -0.4}, {-0.25, 0.3, -0.2}};
  const std::vector<cv::Vec3d> shifts = {{0, 0, 300},    {-45, -35, 320}, {45, 35, 310}, {-45, 35, 330},
                                         {45, -35, 300}, {0, -35, 340},   {-45, 0, 310}, {45, 0, 320}};
  std::vector<cv::Mat> images;
  for (std::size_t i = 0; i < rotations.size(); ++i)
    images.push_back(render_board(inner, square, K, rotations[i], shifts[i], image));
  const ChessboardCalibration c = calibrate_chessboard(images, inner, square);
  const std::string got =
      fmt::format("fx {:.3f} fy {:.3f} cx {:.3f} cy {:.3f} rms {:.4f} px, k1 {:.4g} k2 {:.4g}", c.fx, c.fy,
                  c.intrinsics.cx, c.intrinsics.cy, c.rms_px, c.distortion[0], c.distortion[1]);
  EXPECT_NEAR(c.intrinsics.focal_px / f, 1.0, kFocalTolerance) << got;
  RecordProperty("chessboard", got);
  EXPECT_NEAR(c.fx / c.fy, 1.0, kFocalTolerance);
  EXPECT_NEAR(c.intrinsics.cx, 320.5, kPrincipalPointTolerancePx);
  EXPECT_NEAR(c.intrinsics.cy, 240.5, kPrincipalPointTolerancePx);
  EXPECT_LT(c.rms_px, 0.5);  // corners of a clean rendering reproject to well under a pixel
  EXPECT_EQ(c.images, 8);
  EXPECT_EQ(c.per_image_rms_px.size(), 8U);
  EXPECT_EQ(c.distortion.size(), 5U);
}

TEST(Chessboard, NamesTheImageWithoutCorners) {
  const cv::Size inner(8, 6), image(640, 480);
  const cv::Matx33d K(900, 0, 320, 0, 900, 240, 0, 0, 1);
  std::vector<cv::Mat> images;
  for (int i = 0; i < 4; ++i)
    images.push_back(render_board(inner, 10, K, {0.3 * (i - 1.5), 0.2, 0}, {0, 0, 320}, image));
  images[2] = cv::Mat(image, CV_8UC1, cv::Scalar(255));  // a blank frame
  try {
    calibrate_chessboard(images, inner, 10);
    FAIL() << "a blank image must be rejected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("image 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(calibrate_chessboard({images[0], images[1]}, inner, 10), InputError);  // fewer than 3
  EXPECT_THROW(calibrate_chessboard(images, cv::Size(1, 6), 10), InputError);
  EXPECT_THROW(calibrate_chessboard(images, inner, -1), InputError);
}

// ---------------------------------------------------------------------------------------------
// The real wheat grain: 36 photographs -> segmentation -> axis and crop placement -> carving.

// Segmentation of the K-State photographs (dark blue background, yellow-brown grain): OpenCV HSV
// (H 0-180) H in [0, 40] (orange to yellow; the background is H ~ 114), any S (specular highlights
// are white, S ~ 0, also at the outline), V >= 70 (dark noise); the largest outer contour filled.
Mask segment_wheat_photo(const cv::Mat& bgr) {
  cv::Mat hsv, in_range;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  cv::inRange(hsv, cv::Scalar(0, 0, 70), cv::Scalar(40, 255, 255), in_range);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(in_range, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  std::size_t best = 0;
  double best_area = -1;
  for (std::size_t i = 0; i < contours.size(); ++i)
    if (const double a = cv::contourArea(contours[i]); a > best_area) {
      best_area = a;
      best = i;
    }
  cv::Mat filled = cv::Mat::zeros(bgr.size(), CV_8UC1);
  if (!contours.empty()) cv::drawContours(filled, contours, static_cast<int>(best), cv::Scalar(1), cv::FILLED);
  return Mask(filled.cols, filled.rows, std::vector<std::uint8_t>(filled.datastart, filled.dataend));
}

// The original program's answer on its own masks at fine grids (README: 25.4075 at 256^3,
// 25.4009 at 512^3).
constexpr double kWheatReferenceMm3 = 25.40;
// Why 2% and not less: the given masks are not crops of these photographs. They show the grain
// in another placement (crease down; in the photographs it lies on its side), and the original
// crops followed each silhouette's bounding-box centre instead of the turntable axis (which alone
// lowers the hull by ~3% on these photographs). So the two hulls of one grain agree only to the
// concavity bias (+0.6 to +2.5% at 36 views, spec) plus the outline's placement by segmentation
// (0.3 px ~ 2% of volume: H <= 30 gives -0.8%, H <= 40 +1.5%, adding H >= 165 +2.3%). We measure
// +1.5%; 2% is the goal set for this pipeline.
constexpr double kWheatVolumeTolerance = 0.02;
// Frame pixels per crop pixel: the crops were 240 px regions of the frames resized to 200 px.
// Silhouettes alone cannot fix it (a scaled hull is as consistent); evidence: the photographs'
// silhouette widths over the turn are 1.19-1.20 times the given masks' (least squares), and the
// crops' focal length 1811.594 = 50000 / 27.6 px is exactly 2173.913 / 1.2. Volume goes as
// scale^-3: 1.19 gives +4%, 1.21 gives -1%, and 1 (a plain shift) +75%.
constexpr double kCropScale = 1.2;

TEST(WheatPhotographs, CarvedVolumeMatchesTheOriginalProgram) {
  const CarveInput given = read_carve_input(kWheatDir / "carve_input.dat");  // its matrices only, not its masks
  std::vector<Mask> frames;
  std::vector<double> angles;
  for (int i = 0; i < 36; ++i) {
    const auto file = kWheatDir / "images" / fmt::format("view_{:02d}_{:03d}deg.png", i + 1, 10 * i);
    const cv::Mat bgr = cv::imread(file.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(bgr.empty()) << "cannot read " << file;
    frames.push_back(segment_wheat_photo(bgr));
    angles.push_back(10.0 * i * kPi / 180);
  }

  RegistrationOptions opt;
  opt.scale = kCropScale;
  opt.grid = VoxelGrid::cube({0, 0, 0}, 10, 100);
  const Registration reg = register_to_frames(frames, given.views, angles, opt);
  // The photographs turn against the given matrices: the mirrored placement keeps ~5% more volume
  // (25.76 against 24.49 mm^3 on this grid).
  EXPECT_TRUE(reg.placement.mirrored);
  EXPECT_GT(reg.volume_mm3, 1.02 * reg.other_sense_volume_mm3);
  // Axis column 321.54 +- 0.03 from the centroids (the hull volume peaks within 0.13 px of it; 1 px
  // off costs 3-4% of the volume); the grain swings ~20 px (0.86 mm) about it. Origin row: the
  // silhouettes' mean vertical centre, 242.7 (1 px changes the volume by < 0.1%, 10 px by 0.3%).
  EXPECT_NEAR(reg.axis.column, 321.5, 0.5);
  EXPECT_NEAR(reg.axis.row, 242.7, 1.0);
  EXPECT_GT(reg.axis.orbit_radius_px, 10.0);

  const CarveResult r = carve(reg.views, frames, VoxelGrid::cube({0, 0, 0}, 10, 128), {2, false});
  EXPECT_NEAR(r.subvoxel_volume_mm3 / kWheatReferenceMm3, 1.0, kWheatVolumeTolerance)
      << "volume " << r.subvoxel_volume_mm3 << " mm^3, crop origin (" << reg.placement.x0 << ", " << reg.placement.y0
      << ")";
  RecordProperty("volume_mm3", fmt::format("{:.4f}", r.subvoxel_volume_mm3));
  RecordProperty("axis_column", fmt::format("{:.3f}", reg.column));
  RecordProperty("crop_origin", fmt::format("({:.3f}, {:.3f})", reg.placement.x0, reg.placement.y0));
}

}  // namespace
}  // namespace suite::carving
