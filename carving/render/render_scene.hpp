#pragma once
// `seedcarve render`: synthetic ground truth (docs/methods/carving.md). A YAML scene places an analytic
// seed on a turntable and photographs it from every view through the same camera model the
// measurement uses; out come the colour images, the exact masks, the true volume and a profile
// that measures the images with the same calibration.
//
//   shape:
//     type: ellipsoid          # sphere | ellipsoid | superellipsoid | creased_grain
//     semi_axes: [3.6, 1.45, 1.8]   # mm (sphere: radius: 2 mm)
//     exponents: [0.6, 0.9]    # superellipsoid e1, e2
//     crease: [0.35, 0.5]      # creased_grain: radius and depth of the groove, mm
//     tilt: 20 deg             # rotation about the long (x) axis
//     turn: 0 deg              # rotation about the turntable (y) axis
//     centre: [0, 0, 0]        # mm
//   camera: {model: turntable, focal_px: 6000, principal_point: [320, 240], distance: 100 mm}
//   views: 36
//   image: [640, 480]          # px
//   render: {supersampling: 2, blur_px: 0.7, noise: 2, seed: 1}
//   method: carving            # or slicing: a top view (looking down the y axis) and a side view
#include <filesystem>
#include <memory>
#include <string>

#include "carving/render/shapes.hpp"
#include "core/config/config.hpp"

namespace suite::carving {

struct RenderSummary {
  std::string shape;
  double volume_mm3 = 0;
  int views = 0;
};

// The shape a `shape:` section describes.
std::unique_ptr<Shape> read_shape(const config::Section& shape);

// Renders the scene into `out` (view_NN.png, masks/mask_NN.png, truth.json, profile.yaml,
// effective_config.yaml).
RenderSummary render_scene(const config::Config& scene, const std::filesystem::path& out);

}  // namespace suite::carving
