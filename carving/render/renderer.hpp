#pragma once
// A ray caster that turns an analytic shape and a calibrated view into a synthetic photograph and
// its exact silhouette mask (docs/methods/carving.md, "Synthetic ground truth").
//
// Rays are back-projected from the 3x4 matrix P alone:
//   pinhole (P's left 3x3 block M invertible): camera centre C = -M^-1 p4 (the null vector of P),
//     ray through pixel (u, v) in direction M^-1 (u, v, 1), points in front having w > 0;
//   parallel (P's last row (0, 0, 0, k), k != 0): the ray through (u, v) is the line of world
//     points with P X = (u, v, 1) up to the factor k, in direction m1 x m2 (the first two rows of
//     M: the camera's +z axis for P = [s R_rows_1_2 | t]), i.e. the null vector of M oriented so
//     that the camera looks along it.
// The camera's axes in the world, for the light direction, are the Gram-Schmidt orthonormalisation
// of the viewing direction (z) and M's second row (y, image down); x = y x z.
// A pixel (x, y) has its centre at (u, v) = (x, y). The mask marks pixel (x, y) iff the ray
// through its centre hits the shape: exact, whatever the colour options. The colour image is a
// dark blue background and a wheat-brown seed with Lambert shading (colour = albedo x (ambient +
// (1 - ambient) max(0, n . l))), like the K-State photographs
// (data/kstate_wheat_36view: background about BGR (35, 15, 10), lit seed about
// BGR (130, 220, 255), shaded seed about BGR (70, 135, 180)).
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>

#include "carving/camera/camera.hpp"
#include "carving/image/image_io.hpp"
#include "carving/image/mask.hpp"
#include "carving/render/shapes.hpp"

namespace suite::carving {

struct RenderOptions {
  int supersampling = 1;         // s x s rays per pixel for the colour image, 1..16 (mask: centre ray only)
  double blur_sigma_px = 0;      // Gaussian blur of the colour image, pixels; 0 = none
  double noise_sigma = 0;        // additive Gaussian noise per channel, grey levels (0..255 scale); 0 = none
  std::uint64_t noise_seed = 1;  // the noise is a deterministic function of this seed
  cv::Vec3b background_bgr{38, 15, 10};
  cv::Vec3b seed_bgr{95, 180, 240};  // albedo: the colour of a surface facing the light
  double ambient = 0.35;             // fraction of the albedo seen on surfaces facing away from the light
  // Towards the light, in camera coordinates (x right and y down in the image, z from the camera
  // into the scene), so the lamp moves with the camera as on a real rig where the seed turns:
  // the default is from above the image and from the camera's side.
  Eigen::Vector3d light_direction{0, -1, -1};
};

struct RenderedView {
  cv::Mat image;  // CV_8UC3, BGR, view.height x view.width
  Mask mask;      // exact silhouette, 1 = seed
};

// Renders `shape` as seen by `view`. InputError for a view without pixels, a projection that is
// neither pinhole nor parallel, or options out of range (each message names the option).
RenderedView render(const Shape& shape, const View& view, const RenderOptions& options = {});

}  // namespace suite::carving
