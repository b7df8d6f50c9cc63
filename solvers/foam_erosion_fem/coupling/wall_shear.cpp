#include "solvers/foam_erosion_fem/coupling/wall_shear.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "solvers/foam_erosion_fem/io/foam_reader.hpp"

namespace suite::foam_erosion {

namespace fs = std::filesystem;

namespace {

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

std::vector<WallFaceShear> read_wall_shear(const fs::path& case_dir, const fs::path& time_dir,
                                           const std::string& patch, const Fluid& water, const Fluid& air) {
  const auto mesh = PolyMesh::read(case_dir / "constant/polyMesh");
  const auto& p = mesh.patch(patch);
  const auto n = static_cast<std::size_t>(p.faces);
  const auto tau = read_patch_value(time_dir / "wallShearStress", patch, 3, n);
  const auto alpha = read_internal_field(time_dir / "alpha.water", 1, static_cast<std::size_t>(mesh.cells()));
  std::vector<WallFaceShear> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int f = p.start_face + static_cast<int>(i);
    const Eigen::Vector3d c = mesh.face_centre(f);
    const Eigen::Vector3d s = mesh.face_area(f);
    const Eigen::Vector3d unit = s.normalized();
    const Eigen::Vector3d t(tau.at(i, 0), tau.at(i, 1), tau.at(i, 2));
    const double a = std::clamp(alpha.at(static_cast<std::size_t>(mesh.owner[static_cast<std::size_t>(f)])), 0.0, 1.0);
    const double rho = a * water.density + (1.0 - a) * air.density;
    // The slab's faces span its thickness in z; their length in the section is |S| / thickness.
    double z_min = std::numeric_limits<double>::infinity(), z_max = -z_min;
    for (int q : mesh.faces[static_cast<std::size_t>(f)]) {
      z_min = std::min(z_min, mesh.points[static_cast<std::size_t>(q)].z());
      z_max = std::max(z_max, mesh.points[static_cast<std::size_t>(q)].z());
    }
    out[i].centre = {c.x(), c.y()};
    out[i].length = z_max > z_min ? s.norm() / (z_max - z_min) : s.norm();
    out[i].alpha = a;
    out[i].shear = rho * (t - t.dot(unit) * unit).norm();
  }
  return out;
}

std::vector<double> shear_on_elements(const std::vector<Eigen::Vector2d>& nodes,
                                      const std::vector<WallFaceShear>& faces) {
  if (nodes.size() < 2) throw std::invalid_argument("shear_on_elements: the curve needs at least two nodes");
  if (faces.empty()) throw std::invalid_argument("shear_on_elements: no wall faces to take the shear from");
  const std::size_t elements = nodes.size() - 1;
  std::vector<double> weighted(elements, 0.0), length(elements, 0.0);
  for (const auto& f : faces) {
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < elements; ++e) {
      const double d = distance_to_segment(f.centre, nodes[e], nodes[e + 1]);
      if (d < best_d) best_d = d, best = e;
    }
    weighted[best] += f.length * f.shear;
    length[best] += f.length;
  }
  std::vector<double> out(elements, 0.0);
  for (std::size_t e = 0; e < elements; ++e) {
    if (length[e] > 0.0) {
      out[e] = weighted[e] / length[e];
      continue;
    }
    // The nearest elements with faces on either side along the curve, averaged if both exist.
    double sum = 0.0;
    int count = 0;
    for (std::size_t k = 1; k < elements && count == 0; ++k) {
      if (e >= k && length[e - k] > 0.0) sum += weighted[e - k] / length[e - k], ++count;
      if (e + k < elements && length[e + k] > 0.0) sum += weighted[e + k] / length[e + k], ++count;
    }
    out[e] = count > 0 ? sum / count : 0.0;
  }
  return out;
}

}  // namespace suite::foam_erosion
