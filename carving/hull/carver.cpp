#include "carving/hull/carver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace suite::carving {
namespace {

// The pixel a coordinate rounds to (pixel centres at integers).
inline int pixel_of(double u) {
  return static_cast<int>(std::floor(u + 0.5));
}

enum class Verdict { empty, full, straddle };

void check_inputs(const std::vector<View>& views, const std::vector<Mask>& masks, const VoxelGrid& grid) {
  if (views.empty()) throw InputError("carving needs at least one view");
  if (views.size() != masks.size())
    throw InputError(
        fmt::format("carving got {} views but {} masks; give one mask per view", views.size(), masks.size()));
  for (std::size_t v = 0; v < views.size(); ++v)
    if (masks[v].width() != views[v].width || masks[v].height() != views[v].height)
      throw InputError(fmt::format("view {}: the mask is {} x {} px but the camera's image is {} x {} px", v,
                                   masks[v].width(), masks[v].height(), views[v].width, views[v].height));
  if (grid.n[0] < 1 || grid.n[1] < 1 || grid.n[2] < 1 || !(grid.voxel.minCoeff() > 0))
    throw InputError(fmt::format("carving grid {} x {} x {} with voxel {} mm is empty", grid.n[0], grid.n[1], grid.n[2],
                                 grid.voxel.minCoeff()));
}

class Carver {
 public:
  Carver(const std::vector<View>& views, const std::vector<Mask>& masks, const VoxelGrid& grid,
         const CarveOptions& options)
      : views_(views), masks_(masks), grid_(grid), options_(options), extent_(options.subvoxel_samples > 0) {
    result_.grid = grid;
    result_.first = grid.n;  // shrinks to the kept voxels
  }

  CarveResult run() {
    const int longest = std::max({grid_.n[0], grid_.n[1], grid_.n[2]});
    int top = 1, depth = 1;
    while (top * 8 < longest) top *= 2, ++depth;
    scratch_.assign(depth + 2, std::vector<int>(views_.size()));
    std::vector<int> all(views_.size());
    for (std::size_t v = 0; v < all.size(); ++v) all[v] = static_cast<int>(v);
    for (int k = 0; k < grid_.n[2]; k += top)
      for (int j = 0; j < grid_.n[1]; j += top)
        for (int i = 0; i < grid_.n[0]; i += top) visit(i, j, k, top, all.data(), static_cast<int>(all.size()), 0);
    if (result_.voxels == 0) result_.first = {0, 0, 0};
    result_.volume_mm3 = static_cast<double>(result_.voxels) * grid_.voxel_volume();
    const double per_voxel = std::pow(options_.subvoxel_samples, 3);
    result_.subvoxel_volume_mm3 =
        extent_ ? static_cast<double>(kept_samples_) / per_voxel * grid_.voxel_volume() : result_.volume_mm3;
    return std::move(result_);
  }

 private:
  // Which pixels can the box [a, b] land on in view v, and are they all, some or none seed?
  Verdict test_box(int v, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    ++result_.stats.view_tests;
    const Projection& P = views_[v].P;
    const Eigen::Vector3d p0 = P.leftCols<3>() * a + P.col(3);
    const Eigen::Vector3d d = b - a;
    const Eigen::Vector3d ex = P.col(0) * d.x(), ey = P.col(1) * d.y(), ez = P.col(2) * d.z();
    double umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    for (int c = 0; c < 8; ++c) {
      Eigen::Vector3d q = p0;
      if (c & 1) q += ex;
      if (c & 2) q += ey;
      if (c & 4) q += ez;
      if (!(q.z() > 0))
        throw InputError(
            fmt::format("the carving box reaches behind camera {} (corner depth {}); make the box "
                        "smaller or check the camera distance",
                        v, q.z()));
      const double u = q.x() / q.z(), w = q.y() / q.z();
      umin = std::min(umin, u), umax = std::max(umax, u);
      vmin = std::min(vmin, w), vmax = std::max(vmax, w);
    }
    const Mask& m = masks_[v];
    int x0 = pixel_of(umin), x1 = pixel_of(umax), y0 = pixel_of(vmin), y1 = pixel_of(vmax);
    if (x1 < 0 || y1 < 0 || x0 >= m.width() || y0 >= m.height()) return Verdict::empty;
    const bool clipped = x0 < 0 || y0 < 0 || x1 >= m.width() || y1 >= m.height();
    x0 = std::max(x0, 0), y0 = std::max(y0, 0);
    x1 = std::min(x1, m.width() - 1), y1 = std::min(y1, m.height() - 1);
    const long long seed = m.count(x0, y0, x1, y1);
    if (seed == 0) return Verdict::empty;
    if (!clipped && seed == static_cast<long long>(x1 - x0 + 1) * (y1 - y0 + 1)) return Verdict::full;
    return Verdict::straddle;
  }

  bool test_point(int v, const Eigen::Vector3d& X) {
    ++result_.stats.point_tests;
    const Projection& P = views_[v].P;
    const Eigen::Vector3d q = P.leftCols<3>() * X + P.col(3);
    return masks_[v].inside(pixel_of(q.x() / q.z()), pixel_of(q.y() / q.z()));
  }

  bool test_point_all(const int* active, int n_active, const Eigen::Vector3d& X) {
    for (int a = 0; a < n_active; ++a)
      if (!test_point(active[a], X)) return false;
    return true;
  }

  void keep_range(int i0, int j0, int k0, int i1, int j1, int k1) {
    result_.first = {std::min(result_.first[0], i0), std::min(result_.first[1], j0), std::min(result_.first[2], k0)};
    result_.last = {std::max(result_.last[0], i1), std::max(result_.last[1], j1), std::max(result_.last[2], k1)};
  }

  void visit(int i0, int j0, int k0, int size, const int* active, int n_active, int depth) {
    const int i1 = std::min(i0 + size, grid_.n[0]), j1 = std::min(j0 + size, grid_.n[1]),
              k1 = std::min(k0 + size, grid_.n[2]);
    ++result_.stats.cells;
    if (size == 1 && !extent_) {  // one voxel centre: one pixel per view
      if (!test_point_all(active, n_active, grid_.centre(i0, j0, k0))) return;
      ++result_.voxels;
      keep_range(i0, j0, k0, i0, j0, k0);
      if (options_.keep_cells) result_.boundary.push_back({i0, j0, k0, 1.0f, true});
      return;
    }
    Eigen::Vector3d a, b;
    if (extent_) {
      a = grid_.lo + Eigen::Vector3d(i0 * grid_.voxel.x(), j0 * grid_.voxel.y(), k0 * grid_.voxel.z());
      b = grid_.lo + Eigen::Vector3d(i1 * grid_.voxel.x(), j1 * grid_.voxel.y(), k1 * grid_.voxel.z());
    } else {
      a = grid_.centre(i0, j0, k0);
      b = grid_.centre(i1 - 1, j1 - 1, k1 - 1);
    }
    int* left = scratch_[depth].data();
    int n_left = 0;
    for (int t = 0; t < n_active; ++t) {
      const Verdict verdict = test_box(active[t], a, b);
      if (verdict == Verdict::empty) return;
      if (verdict == Verdict::straddle) left[n_left++] = active[t];
    }
    if (n_left == 0) {  // every view keeps the whole cell
      const long long count = static_cast<long long>(i1 - i0) * (j1 - j0) * (k1 - k0);
      result_.voxels += count;
      kept_samples_ += count * options_.subvoxel_samples * options_.subvoxel_samples * options_.subvoxel_samples;
      keep_range(i0, j0, k0, i1 - 1, j1 - 1, k1 - 1);
      if (options_.keep_cells) result_.inside.push_back({i0, j0, k0, size});
      return;
    }
    if (size == 1) {  // a boundary voxel: its centre, and s^3 samples for the sub-voxel volume
      const bool centre = test_point_all(left, n_left, grid_.centre(i0, j0, k0));
      const int s = options_.subvoxel_samples;
      int kept = 0;
      for (int c = 0; c < s; ++c)
        for (int bb = 0; bb < s; ++bb)
          for (int aa = 0; aa < s; ++aa) {
            const Eigen::Vector3d X =
                a + Eigen::Vector3d((aa + 0.5) / s * grid_.voxel.x(), (bb + 0.5) / s * grid_.voxel.y(),
                                    (c + 0.5) / s * grid_.voxel.z());
            kept += test_point_all(left, n_left, X) ? 1 : 0;
          }
      const float fraction = static_cast<float>(kept) / static_cast<float>(s * s * s);
      kept_samples_ += kept;
      if (centre) {
        ++result_.voxels;
        keep_range(i0, j0, k0, i0, j0, k0);
      }
      if (options_.keep_cells && (centre || kept > 0)) result_.boundary.push_back({i0, j0, k0, fraction, centre});
      return;
    }
    const int half = size / 2;
    for (int c = 0; c < 8; ++c) {
      const int ci = i0 + ((c & 1) ? half : 0), cj = j0 + ((c & 2) ? half : 0), ck = k0 + ((c & 4) ? half : 0);
      if (ci < grid_.n[0] && cj < grid_.n[1] && ck < grid_.n[2]) visit(ci, cj, ck, half, left, n_left, depth + 1);
    }
  }

  const std::vector<View>& views_;
  const std::vector<Mask>& masks_;
  VoxelGrid grid_;
  CarveOptions options_;
  bool extent_;
  CarveResult result_;
  long long kept_samples_ = 0;             // sub-samples kept, s^3 per voxel of an inside cell
  std::vector<std::vector<int>> scratch_;  // the views still undecided, one list per depth
};

}  // namespace

CarveResult carve(const std::vector<View>& views, const std::vector<Mask>& masks, const VoxelGrid& grid,
                  const CarveOptions& options) {
  check_inputs(views, masks, grid);
  if (options.subvoxel_samples < 0 || options.subvoxel_samples > 16)
    throw InputError(fmt::format("subvoxel_samples = {}: give 0 (voxel centres only) to 16", options.subvoxel_samples));
  return Carver(views, masks, grid, options).run();
}

long long carve_plain(const std::vector<View>& views, const std::vector<Mask>& masks, const VoxelGrid& grid) {
  check_inputs(views, masks, grid);
  long long kept = 0;
  for (int k = 0; k < grid.n[2]; ++k)
    for (int j = 0; j < grid.n[1]; ++j)
      for (int i = 0; i < grid.n[0]; ++i) {
        const Eigen::Vector3d X = grid.centre(i, j, k);
        bool in = true;
        for (std::size_t v = 0; v < views.size() && in; ++v) {
          const Eigen::Vector3d q = views[v].P.leftCols<3>() * X + views[v].P.col(3);
          in = masks[v].inside(pixel_of(q.x() / q.z()), pixel_of(q.y() / q.z()));
        }
        kept += in ? 1 : 0;
      }
  return kept;
}

}  // namespace suite::carving
