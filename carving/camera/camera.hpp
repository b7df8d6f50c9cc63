#pragma once
// Camera models for seed imaging (docs/methods/carving.md).
//
// A view maps world points (mm) to pixel coordinates with a 3x4 matrix P: (u, v, w) = P (X, 1),
// pixel (u/w, v/w). u runs along image columns (x, to the right), v along rows (y, down), and a
// pixel's centre has integer coordinates: pixel (x, y) covers [x - 0.5, x + 0.5) x [y - 0.5, y + 0.5).
// This is the convention of the Kansas State carving program (data/kstate_wheat_36view).
//
// Turntable: the seed turns about the world y axis (image "down" at angle 0); view i sees the
// world rotated by R_y(angle_i) and moved `distance` along the optical axis: P = K [R_y | (0,0,d)].
// A parallel (orthographic) camera has the last row (0, 0, 0, 1) and the same formula.
#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace suite::carving {

using Projection = Eigen::Matrix<double, 3, 4>;

// One calibrated view: its projection and the size of its image in pixels.
struct View {
  Projection P = Projection::Zero();
  int width = 0;
  int height = 0;
};

// Pixel coordinates of world point X (mm). Requires a positive depth (w > 0).
inline Eigen::Vector2d project(const Projection& P, const Eigen::Vector3d& X) {
  const Eigen::Vector3d p = P.leftCols<3>() * X + P.col(3);
  return {p.x() / p.z(), p.y() / p.z()};
}

// Intrinsics: focal length in pixels and principal point.
struct Intrinsics {
  double focal_px = 0;
  double cx = 0;
  double cy = 0;
  Eigen::Matrix3d matrix() const;
};

// A pinhole camera: P = K [R | t] (R world-to-camera rotation, t the world origin in camera
// coordinates, mm).
Projection pinhole_projection(const Intrinsics& K, const Eigen::Matrix3d& R, const Eigen::Vector3d& t);

// A parallel camera: pixel = s (R X)_xy + (cx, cy), with R the world-to-camera rotation and s
// pixels per mm; the last row of P is (0, 0, 0, 1).
Projection parallel_projection(double scale_px_per_mm, double cx, double cy, const Eigen::Matrix3d& R);

// Rotation about the world y axis (the turntable axis) by `angle` radians.
Eigen::Matrix3d rotation_about_axis(double angle);

// A turntable rig: `views` images at angles first_angle + i * step (radians) about the y axis.
struct Turntable {
  Intrinsics K;
  double distance_mm = 0;  // camera centre to the axis
  int views = 0;
  double first_angle = 0;
  double step = 0;  // 2 pi / views when the full circle is covered
  int width = 0, height = 0;

  double angle(int i) const { return first_angle + step * i; }
  Projection projection(int i) const;
  std::vector<View> all_views() const;
};

// A parallel-projection turntable (telecentric lens, or the limit of a far camera): `scale`
// pixels per mm, the axis projecting to column cx, the world origin to row cy.
struct ParallelTurntable {
  double scale_px_per_mm = 0;
  double cx = 0, cy = 0;
  int views = 0;
  double first_angle = 0;
  double step = 0;
  int width = 0, height = 0;

  Projection projection(int i) const;
  std::vector<View> all_views() const;
};

// A text file of projection matrices: 12 numbers per view, row by row (P11 P12 P13 P14 P21 ...),
// in any whitespace layout; '#' starts a comment. `expected` (> 0) is the number of views the
// caller has images for; a different count is an InputError naming the file and both counts.
std::vector<Projection> read_projection_file(const std::filesystem::path& file, int expected);

}  // namespace suite::carving
