#pragma once
// A calibration profile: how one kind of seed on one rig is imaged and measured (docs/methods/carving.md).
// A YAML file, e.g. examples/profiles/wheat_turntable.yaml:
//
//   method: carving                 # carving (multi-view) | slicing (top + side view)
//   segmentation:                   # OpenCV HSV ranges: H 0..180, S and V 0..255
//     hsv_low: [0, 60, 0]
//     hsv_high: [30, 255, 255]
//     automatic: false              # true: Otsu threshold instead of the range
//     open_px: 3                    # morphological clean-up kernels
//     close_px: 3
//     area_px: [15000, 50000]       # plausible contour areas; others are noise
//   camera:                         # carving: the turntable, or a file of projection matrices
//     model: turntable              # turntable | parallel | projection_file
//     focal_px: 1811.594
//     principal_point: [100, 100]   # px, in the calibrated image
//     distance: 93.108 mm           # camera centre to the turntable axis
//     first_angle: 0 deg
//     step: 10 deg                  # default: a full turn over the images
//     views: 36                     # optional: a seed with another number of images fails
//     frame_origin: [220, 38]       # where the calibrated image's pixel (0, 0) lies in the
//                                   # photographs, or `auto` (found from the turn itself)
//     frame_scale: 1                # photograph px per calibrated px (crops that were resized)
//     frame_turn: same              # same | reversed: the photographs see the turntable turn the
//                                   # other way from the calibration; with `auto` origin also `auto`
//   carving: {resolution: 256, subvoxel_samples: 0, search_resolution: 48, mesh: true, mesh_resolution: 128,
//             voxels_h5: false}      # voxels.h5: occupancy fractions on the mesh grid (io/voxel_output.hpp)
//   slicing: {slices: 50, px_per_mm: 40, scale_correction: true,    # slicing: images are [top, side]
//             neighbour_average: false}  # true: each column's contour points averaged over 5 columns
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "carving/calibration/turntable_axis.hpp"
#include "carving/camera/camera.hpp"
#include "carving/image/segmentation.hpp"
#include "carving/measure/hull_measurement.hpp"
#include "carving/slicing/two_view.hpp"
#include "core/config/config.hpp"

namespace suite::carving {

struct CameraProfile {
  std::string model = "turntable";      // turntable | parallel | projection_file
  Intrinsics K;                         // turntable
  double distance_mm = 0;               // turntable
  double px_per_mm = 0;                 // parallel
  double first_angle = 0;               // radians
  std::optional<double> step;           // radians; default 2 pi / images
  std::optional<int> views;             // the images a seed must have (carving), when given
  std::vector<Projection> projections;  // projection_file
  std::filesystem::path projection_file;
  bool auto_frame_origin = false;
  Eigen::Vector2d frame_origin{0, 0};
  double frame_scale = 1;
  int frame_turn = 1;  // +1 same sense as the calibration, -1 reversed, 0 decide (auto origin only)
};

struct SeedProfile {
  std::string method = "carving";
  SegmentationOptions segmentation;
  CameraProfile camera;
  HullOptions hull;
  SlicingOptions slicing;
  std::string source;          // the profile file, for messages
  std::string effective_yaml;  // as used, defaults included
};

// The `segmentation:` section of a profile.
SegmentationOptions read_segmentation(const config::Section& segmentation);

// The `camera:` section of a profile (or of a render scene).
CameraProfile read_camera_profile(const config::Section& camera);

// Reads and checks a profile (unknown keys are errors with a suggestion).
SeedProfile read_seed_profile(const config::Config& cfg);

// The calibrated views for `images` photographs of `width` x `height` px, frame placement applied
// (frame_origin, frame_scale, frame_turn); with `frame_origin: auto` the calibration as it is
// (seed_views() places it).
std::vector<View> profile_views(const CameraProfile& camera, int images, int width, int height);

// The turntable angle of each of `images` views (first_angle + i step; step defaults to a full turn).
std::vector<double> profile_angles(const CameraProfile& camera, int images);

// The views for one seed's silhouettes: profile_views(), or with `frame_origin: auto` the
// calibration registered to the silhouettes (calibration/turntable_axis.hpp: axis column and
// origin row from the turn, frame_scale, and the sense of rotation chosen by hull volume on the
// search cube when frame_turn is auto). `registration` is set in the auto case.
std::vector<View> seed_views(const CameraProfile& camera, const HullOptions& hull, const std::vector<Mask>& masks,
                             std::optional<Registration>& registration);

}  // namespace suite::carving
