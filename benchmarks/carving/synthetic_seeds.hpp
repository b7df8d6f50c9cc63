#pragma once
// Analytic seeds photographed by turntable rigs for the carving benchmarks, with the renderer's
// exact silhouettes (RenderedView::mask, one ray through each pixel centre), so that only the
// carving method's error shows, not segmentation's.
//
// Rigs (world y is the turntable axis, the seed centred on it; view i at angle i * 360/N deg):
//   parallel sphere: radius 2 mm, `px_per_mm` (the analytic visual hull holds here), an image of
//                    2.5 radii square;
//   pinhole sphere:  radius 2 mm, camera 50 mm (25 radii) from the axis, focal length `focal_px`
//                    (5000 px: 200 px per radius), an image of 2.5 image radii square;
//   wheat ellipsoid: 7.2 x 2.9 x 3.6 mm tilted 20 deg about its long axis, f = 6000 px, 100 mm,
//                    640 x 480 px (carving/examples/synthetic/wheat_ellipsoid.yaml);
//   creased grain:   7.2 x 3.6 x 2.9 mm less a groove (radius, depth) along the ventral side, tilted
//                    90 deg (crease facing along the axis) and turned by `turn` about the axis, on
//                    the wheat rig (carving/examples/synthetic/creased_grain.yaml).
#include <memory>
#include <string>
#include <vector>

#include "carving/camera/camera.hpp"
#include "carving/hull/voxel_grid.hpp"
#include "carving/image/mask.hpp"
#include "carving/render/shapes.hpp"

namespace suite::carving::bench {

struct SyntheticSeed {
  std::string name;        // e.g. "sphere_parallel"
  std::string projection;  // "parallel" or "pinhole"
  std::shared_ptr<const Shape> shape;
  std::vector<View> views;  // a full turn, equally spaced
  std::vector<Mask> masks;  // exact silhouettes, one per view
  double cube_side_mm = 0;  // the carved cube, centred on the origin; holds the visual hull from >= 6 views

  VoxelGrid cube(int cells) const { return VoxelGrid::cube({0, 0, 0}, cube_side_mm, cells); }
};

// `views` views over a full turn of each rig, rendered.
SyntheticSeed parallel_sphere(int views, double px_per_mm);
SyntheticSeed pinhole_sphere(int views, double focal_px);
SyntheticSeed wheat_ellipsoid(int views);
SyntheticSeed creased_grain(int views, double crease_radius_mm, double crease_depth_mm, double turn_rad);
// The creased grain's ellipsoid without the groove, same pose and rig (separates the hull's
// convex bias from what the crease hides).
SyntheticSeed uncreased_grain(int views, double turn_rad);

// Every (views / n)-th view and mask: n views equally spaced over the same full turn. `n` must
// divide the seed's view count.
SyntheticSeed every_nth_view(const SyntheticSeed& seed, int n);

// Visual-hull volume of a sphere of radius r from n equally spaced parallel views over a full
// turn (docs/methods/carving.md): a stack of regular polygons with n sides (n even; 2n for odd n), so
// V = (4 sides / 3) tan(pi / sides) r^3.
double analytic_sphere_hull_mm3(int views, double radius_mm);

}  // namespace suite::carving::bench
