#pragma once
// Analytic seed shapes with known volume, the synthetic ground truth of docs/methods/carving.md: sphere,
// ellipsoid, superellipsoid and a creased grain (an ellipsoid with a groove along its long axis).
//
// Every shape has a pose: a rotation R (body axes to world axes) and a centre c, both in mm, so a
// body point p sits at world point X = R p + c. Body axes: x is the long axis (semi-axis a), y the
// width (b), z the thickness (c). The interface works in world coordinates:
//   implicit(X)   negative inside, zero on the surface, positive outside (about mm near the surface;
//                 the superellipsoid's is its gauge minus 1, dimensionless)
//   contains(X)   implicit(X) < 0
//   volume()      exact (closed form), or for CreasedGrain an adaptive quadrature done once
//   first_hit()   the first point of a ray in the shape, for rendering exact silhouettes
//   normal(X)     outward unit normal at a surface point, for shading
#include <Eigen/Core>
#include <optional>
#include <string>

namespace suite::carving {

// Position and orientation of a shape: world = rotation * body + centre (mm).
struct Pose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

struct BoundingSphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
};

class Shape {
 public:
  explicit Shape(const Pose& pose);
  virtual ~Shape() = default;

  const Pose& pose() const { return pose_; }
  virtual std::string name() const = 0;
  virtual double volume() const = 0;  // mm^3

  double implicit(const Eigen::Vector3d& X) const { return local_implicit(to_body(X)); }
  bool contains(const Eigen::Vector3d& X) const { return implicit(X) < 0; }
  BoundingSphere bounding_sphere() const { return {pose_.centre, local_radius()}; }

  // The smallest t >= 0 such that origin + t * direction / |direction| lies in the (closed) shape:
  // the distance in mm along the ray to the first surface point, 0 when the origin is inside, and
  // nothing when the ray misses. `direction` need not be a unit vector but must not be zero.
  std::optional<double> first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

  // Outward unit normal at (or very near) a surface point X.
  Eigen::Vector3d normal(const Eigen::Vector3d& X) const;

 protected:
  Eigen::Vector3d to_body(const Eigen::Vector3d& X) const { return pose_.rotation.transpose() * (X - pose_.centre); }

  virtual double local_implicit(const Eigen::Vector3d& p) const = 0;
  // Radius of a sphere about the body origin that holds the shape.
  virtual double local_radius() const = 0;
  // First hit of the ray p + t d (|d| = 1, body coordinates) with t >= 0. The default samples the
  // implicit function inside the bounding sphere every sampling_step() mm and refines the first
  // sign change (regula falsi with bisection steps) to 1e-12 of the radius; a chord shorter than
  // the step can be missed.
  virtual std::optional<double> local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const;
  virtual double sampling_step() const { return local_radius() / 1024; }
  // The default normal is the normalised central-difference gradient of local_implicit.
  virtual Eigen::Vector3d local_normal(const Eigen::Vector3d& p) const;

 private:
  Pose pose_;
};

class Sphere final : public Shape {
 public:
  explicit Sphere(double radius_mm, const Pose& pose = {});
  std::string name() const override { return "sphere"; }
  double volume() const override;
  double radius() const { return r_; }

 protected:
  double local_implicit(const Eigen::Vector3d& p) const override { return p.norm() - r_; }
  double local_radius() const override { return r_; }
  std::optional<double> local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const override;
  Eigen::Vector3d local_normal(const Eigen::Vector3d& p) const override { return p.normalized(); }

 private:
  double r_;
};

// (x/a)^2 + (y/b)^2 + (z/c)^2 <= 1 in body coordinates; a, b, c are semi-axes (mm), so a wheat
// grain of 7.2 x 3.6 x 2.9 mm is Ellipsoid(3.6, 1.8, 1.45).
class Ellipsoid final : public Shape {
 public:
  Ellipsoid(double a, double b, double c, const Pose& pose = {});
  std::string name() const override { return "ellipsoid"; }
  double volume() const override;
  Eigen::Vector3d semi_axes() const { return axes_; }

 protected:
  double local_implicit(const Eigen::Vector3d& p) const override;
  double local_radius() const override { return axes_.maxCoeff(); }
  std::optional<double> local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const override;
  Eigen::Vector3d local_normal(const Eigen::Vector3d& p) const override;

 private:
  Eigen::Vector3d axes_;
};

// Barr's superellipsoid: F = (|x/a|^(2/e2) + |y/b|^(2/e2))^(e2/e1) + |z/c|^(2/e1) <= 1.
// e1 shapes the profile along z, e2 the cross-section in x-y; e1 = e2 = 1 is the ellipsoid, small
// exponents tend to a box. Volume 2abc e1 e2 B(e1/2 + 1, e1) B(e2/2, e2/2) (B the beta function).
// Exponents must lie in [0.1, 4]. For e1, e2 <= 2 the shape is convex and first_hit minimises the
// implicit function along the ray (convex there) by golden sections, stopping at the first inside
// point or once a convexity lower bound proves a miss, then refines the crossing: hit or miss is
// decided exactly up to about 1e-12 mm. For larger exponents (pinched, non-convex) it samples
// every min(a, b, c)/256 mm, so a chord shorter than that can be missed.
class Superellipsoid final : public Shape {
 public:
  Superellipsoid(double a, double b, double c, double e1, double e2, const Pose& pose = {});
  std::string name() const override { return "superellipsoid"; }
  double volume() const override;
  Eigen::Vector3d semi_axes() const { return axes_; }
  double e1() const { return e1_; }
  double e2() const { return e2_; }

 protected:
  // F^(e1/2) - 1: positively homogeneous of degree 1 in the scaled coordinates, so it behaves like
  // a distance (a gauge) and is convex when the shape is.
  double local_implicit(const Eigen::Vector3d& p) const override;
  double local_radius() const override { return axes_.norm(); }
  std::optional<double> local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const override;
  double sampling_step() const override { return axes_.minCoeff() / 256; }

 private:
  Eigen::Vector3d axes_;
  double e1_, e2_;
};

// A wheat-like grain: the ellipsoid (a, b, c) minus a crease along the long (x) axis on the ventral
// side (z < 0). The crease is a round-bottomed slot of width 2 crease_radius running the whole
// length: in every cross-section x = const it removes the U-shaped region
//   |y| < crease_radius and z < z_c + sqrt(crease_radius^2 - y^2),   z_c = -c + crease_depth - crease_radius,
// i.e. the disc of radius crease_radius about (y, z) = (0, z_c) and everything below its centre.
// Its roof is at z = -c + crease_depth: crease_depth deep at the middle, shallower towards the
// ends where the underside rises, and gone where the underside is above the roof. The slot is
// open to the outside, so it is a true concavity: silhouettes seen along z (top view) and along
// y (side view) do not show it; views along x (end-on) do.
//
// Volume = ellipsoid volume - groove volume. The groove volume is an adaptive Gauss-Kronrod
// (7/15 point) quadrature over x of an adaptive quadrature over y of the exact z-chord that the
// slot removes, done once in the constructor to `volume_tolerance` mm^3;
// volume_error_estimate() is the outer quadrature's |K15 - G7| sum plus the length times the
// inner tolerance, a conservative bound (the Kronrod estimate is far smaller in practice).
// first_hit and normal are analytic (ray-ellipsoid interval minus the ray's interval in the slot,
// a convex prism).
class CreasedGrain final : public Shape {
 public:
  CreasedGrain(double a, double b, double c, double crease_radius, double crease_depth, const Pose& pose = {},
               double volume_tolerance = 1e-9);
  std::string name() const override { return "creased grain"; }
  double volume() const override { return volume_; }
  double volume_error_estimate() const { return volume_error_; }
  double ellipsoid_volume() const;
  Eigen::Vector3d semi_axes() const { return axes_; }
  // Length (mm) of the body's intersection with the body-frame line through (x, y) parallel to the
  // z axis: the integrand of the volume, public so tests can integrate it independently.
  double chord_length_z(double x, double y) const;

 protected:
  double local_implicit(const Eigen::Vector3d& p) const override;
  double local_radius() const override { return axes_.maxCoeff(); }
  std::optional<double> local_first_hit(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const override;
  Eigen::Vector3d local_normal(const Eigen::Vector3d& p) const override;

 private:
  double groove_chord(double x, double y) const;           // z-length the slot removes at (x, y)
  double groove_distance(const Eigen::Vector3d& p) const;  // signed distance to the slot, < 0 inside

  Eigen::Vector3d axes_;
  double crease_radius_, crease_depth_, crease_z_;
  double volume_ = 0, volume_error_ = 0;
};

// A rotation matrix from a unit-free axis (need not be normalised) and an angle in radians.
Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& axis, double angle);

}  // namespace suite::carving
