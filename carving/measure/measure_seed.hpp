#pragma once
// One seed from its images to its results row (docs/methods/carving.md): read and segment every image,
// then either carve the silhouettes (multi-view) or slice the top and side views (two-view),
// and write what a person needs to check the result into the seed's folder:
//   overlays.png  every view with the chosen contour (carving) or the slices (two-view)
//   surface.ply   the marching-cubes surface (carving, when the profile asks for a mesh)
//   seed.json     the measurement, the calibration used and timings
// Never throws for a bad seed: the row says "failed" and why (the file, the view, the reason).
#include <filesystem>

#include "carving/batch/manifest.hpp"
#include "carving/batch/results_table.hpp"
#include "carving/measure/seed_profile.hpp"

namespace suite::carving {

SeedRow measure_seed(const SeedEntry& seed, const SeedProfile& profile, const std::filesystem::path& seed_dir);

}  // namespace suite::carving
