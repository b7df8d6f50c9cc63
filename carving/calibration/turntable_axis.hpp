#pragma once
// Turntable calibration from the silhouettes themselves (docs/methods/carving.md, "Calibration"), and moving
// views calibrated for crops of the camera frames into the frames.
//
// Axis column. Under a parallel view the silhouette at angle theta + pi is the mirror image, about
// the axis column, of the silhouette at theta, so the horizontal centroid of the silhouette minus
// the axis column changes sign over half a turn: as a function of the angle it holds only odd
// harmonics. estimate_axis() fits  x_c(theta) = column + sum over odd k of (a_k cos k theta +
// b_k sin k theta)  (k = 1, 3, ... up to 9, as many as the views allow) by least squares; for a full
// turn of equally spaced views the column is the mean of the centroids. Under a pinhole view the
// mirror symmetry breaks: the end of an elongated seed nearer the camera looks larger, which moves
// the centroid by up to a pixel or two (a 7 mm grain at 93 mm) with period half a turn, so from
// 12 views on the fit also has a k = 2 term. (A seed's offset from the axis adds only terms of
// order (offset / distance)^2, a tenth of a pixel for 1 mm at 93 mm.)
//
// Crops. A calibration made for crops of the frames (the Kansas State data: 200 x 200 crops with
// P = K [R_y | t]) reaches the frame through an image-space map: frame pixel = A * crop pixel with
// A = [[sx, 0, x0], [0, scale, y0], [0, 0, 1]], sx = scale, or -scale when the frames see the
// turntable turn the other way from the crops' matrices (a horizontal mirror about the axis is the
// same as reversing the sense of rotation; the carved shape then comes out mirrored, its volume and
// sizes unchanged). Silhouettes alone fix the axis column, the sense of rotation and a sensible
// origin row, but not the scale: a hull scaled about the camera is as consistent as the original.
// The scale must come from how the crops were made (1.2 for the Kansas State crops, 240 px regions
// of the frame resized to 200 px) or from a reference ball (ball.hpp). The Kansas State photographs
// also turn against their crops' matrices (mirrored placement), and their crops followed each
// silhouette's bounding-box centre rather than the axis, so no single placement reproduces the
// given masks; register_to_frames() registers to the turntable's geometry, not to those crops.
#include <Eigen/Core>
#include <vector>

#include "carving/camera/camera.hpp"
#include "carving/hull/voxel_grid.hpp"
#include "carving/image/mask.hpp"

namespace suite::carving {

struct AxisEstimate {
  double column = 0;              // image column of the turntable axis (px; pixel centres at integers)
  double row = 0;                 // mean over views of the silhouette's vertical centre (bounding box): the
                                  // row to put the world origin on, so the seed sits mid-height in the box
  double base_row = 0;            // lowest seed row over the turn: the seed's base line on the turntable
  double residual_px = 0;         // rms residual of the centroid fit (segmentation noise, lighting asymmetry)
  double column_stderr_px = 0;    // standard error of `column` from the fit (0 when nothing is left over)
  double orbit_radius_px = 0;     // first-harmonic amplitude: how far the silhouette centroid swings off the axis
  int harmonics = 0;              // odd harmonics fitted: h means k = 1, 3, ..., 2h - 1
  bool perspective_term = false;  // the k = 2 term was fitted
};

// Needs at least 3 masks of one size, each with seed pixels, with their turntable angles (radians)
// spread so that they fix the first harmonic (e.g. not all within a few degrees); throws
// InputError otherwise, naming the view.
AxisEstimate estimate_axis(const std::vector<Mask>& masks, const std::vector<double>& angles_rad);

// Where a crop sits in a frame: crop pixel (u, v) is frame pixel (sx u + x0, scale v + y0) with
// sx = mirrored ? -scale : scale; (x0, y0) is the frame pixel of the crop's pixel (0, 0).
struct CropPlacement {
  double x0 = 0;
  double y0 = 0;
  double scale = 1;       // frame pixels per crop pixel (> 0)
  bool mirrored = false;  // frames see the turntable turn against the crops' matrices
  Eigen::Matrix3d matrix() const;
};

// Views calibrated for crops, moved into frames of frame_width x frame_height px:
// P_frame = A P_crop (A from `placement`). Throws InputError for a non-positive scale or frame size.
std::vector<View> place_views(const std::vector<View>& calibrated, const CropPlacement& placement, int frame_width,
                              int frame_height);

// The plain shift: P_frame = [[1, 0, x0], [0, 1, y0], [0, 0, 1]] P_crop.
std::vector<View> shift_views(const std::vector<View>& calibrated, double x0, double y0, int frame_width,
                              int frame_height);

struct RegistrationOptions {
  double scale = 1;  // frame pixels per crop pixel: known from how the crops were made (see above)
  // +1: the frames turn the way the crop matrices do; -1: the other way (mirrored placement);
  // 0: decide by the hull volume on `grid` (a wrong sense carves away more of the seed).
  int orientation = 0;
  // > 0: search the axis column over estimate +- this many px in steps of refine_step_px for the
  // largest hull volume on `grid` (the most consistent column); 0 keeps the centroid estimate.
  double refine_half_width_px = 0;
  double refine_step_px = 0.25;
  VoxelGrid grid;  // the box for the volume criterion; needed when orientation == 0 or refining
};

struct Registration {
  AxisEstimate axis;            // from the frame silhouettes
  CropPlacement placement;      // crop -> frame
  double column = 0;            // axis column used (the estimate, or the refined one)
  double crop_axis_column = 0;  // where the crop matrices put the axis (the world origin's image)
  double crop_origin_row = 0;
  double volume_mm3 = 0;  // hull volume (voxel centres) on options.grid at the chosen placement; 0 if not carved
  double other_sense_volume_mm3 = 0;  // the same with the other sense of rotation (orientation 0 only)
  std::vector<View> views;            // the registered frame views, one per frame mask
};

// Registers views calibrated for crops (crop_views, one per frame, all projecting the world origin,
// which lies on the turntable axis, to the same crop pixel) to frame silhouettes taken at
// angles_rad: estimates the axis column and origin row from the frames (estimate_axis), places the
// crops so that the crops' axis lands on that column and their origin on that row, with the given
// scale, decides the sense of rotation and optionally refines the column (see RegistrationOptions).
// Throws InputError when the counts disagree, a crop view does not see the origin at the common
// pixel, or a needed grid is empty.
Registration register_to_frames(const std::vector<Mask>& frame_masks, const std::vector<View>& crop_views,
                                const std::vector<double>& angles_rad, const RegistrationOptions& options);

}  // namespace suite::carving
