#pragma once
// Whether a visual hull explains its silhouettes (docs/methods/carving.md, "Quality checks").
// Every voxel centre the carve keeps projects onto a seed pixel of every view, so the hull's image
// lies inside each silhouette; where the views and the calibration agree it also fills it. Where
// they disagree (a view missing from the turn, angles other than the profile's, a camera off its
// calibration) the other views carve away part of what a view shows, and its silhouette is left
// partly uncovered. The coverage of a view: the fraction of its seed pixels that the hull's image
// covers, the hull's surface voxels painted as discs of the voxel's projected bounding sphere (so
// that a consistent hull covers its silhouettes up to their last pixel).
#include <vector>

#include "carving/camera/camera.hpp"
#include "carving/hull/carver.hpp"
#include "carving/image/mask.hpp"

namespace suite::carving {

// Per view, the coverage in [0, 1] of its mask by the kept voxels of `hull` (a carve made with
// keep_cells), in the order of `views`.
std::vector<double> silhouette_coverage(const std::vector<View>& views, const std::vector<Mask>& masks,
                                        const CarveResult& hull);

}  // namespace suite::carving
