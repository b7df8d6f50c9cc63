#include "carving/measure/silhouette_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

namespace suite::carving {

std::vector<double> silhouette_coverage(const std::vector<View>& views, const std::vector<Mask>& masks,
                                        const CarveResult& hull) {
  const VoxelGrid& g = hull.grid;
  // The kept voxels, then those of them with an empty face neighbour: every line of sight that
  // meets the hull enters it through one of those, so their images cover the hull's.
  const auto nx = static_cast<std::size_t>(g.n[0]), ny = static_cast<std::size_t>(g.n[1]);
  std::vector<std::uint8_t> kept(nx * ny * static_cast<std::size_t>(g.n[2]), 0);
  const auto at = [&](int i, int j, int k) { return static_cast<std::size_t>(i) + nx * (j + ny * k); };
  for_each_kept_voxel(hull, [&](int i, int j, int k) { kept[at(i, j, k)] = 1; });
  const auto empty = [&](int i, int j, int k) {
    return i < 0 || j < 0 || k < 0 || i >= g.n[0] || j >= g.n[1] || k >= g.n[2] || !kept[at(i, j, k)];
  };
  std::vector<Eigen::Vector3d> centres;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        if (kept[at(i, j, k)] && (empty(i - 1, j, k) || empty(i + 1, j, k) || empty(i, j - 1, k) ||
                                  empty(i, j + 1, k) || empty(i, j, k - 1) || empty(i, j, k + 1)))
          centres.push_back(g.centre(i, j, k));
  const double radius_mm = 0.5 * g.voxel.norm();  // the voxel's bounding sphere
  std::vector<double> coverage;
  for (std::size_t v = 0; v < views.size(); ++v) {
    // Painted and counted over the seed pixels' box only (no seed pixel lies outside it; circles
    // reaching beyond it are clipped by OpenCV).
    const Mask& mask = masks[v];
    const Mask::Box box = mask.seed_box();
    if (box.x1 < box.x0) {
      coverage.push_back(0.0);
      continue;
    }
    cv::Mat painted(box.y1 - box.y0 + 1, box.x1 - box.x0 + 1, CV_8U, cv::Scalar(0));
    for (const auto& c : centres) {
      const Eigen::Vector2d p = project(views[v].P, c);
      // The sphere's image radius from the projection of a point one radius away across the view.
      const Eigen::Vector2d q = project(views[v].P, c + Eigen::Vector3d(0, radius_mm, 0));
      const int r = std::max(1, static_cast<int>(std::ceil((q - p).norm())));
      cv::circle(
          painted,
          cv::Point(static_cast<int>(std::lround(p.x())) - box.x0, static_cast<int>(std::lround(p.y())) - box.y0), r,
          cv::Scalar(1), cv::FILLED);
    }
    long long seed = 0, covered = 0;
    for (int y = box.y0; y <= box.y1; ++y) {
      const auto* row = painted.ptr<std::uint8_t>(y - box.y0);
      for (int x = box.x0; x <= box.x1; ++x)
        if (mask.at(x, y)) ++seed, covered += row[x - box.x0] != 0;
    }
    coverage.push_back(static_cast<double>(covered) / static_cast<double>(seed));
  }
  return coverage;
}

}  // namespace suite::carving
