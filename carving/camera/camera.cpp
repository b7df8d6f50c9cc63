#include "carving/camera/camera.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/errors.hpp"

namespace suite::carving {

Eigen::Matrix3d Intrinsics::matrix() const {
  Eigen::Matrix3d K;
  K << focal_px, 0, cx, 0, focal_px, cy, 0, 0, 1;
  return K;
}

Projection pinhole_projection(const Intrinsics& K, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Projection Rt;
  Rt.leftCols<3>() = R;
  Rt.col(3) = t;
  return K.matrix() * Rt;
}

Eigen::Matrix3d rotation_about_axis(double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix3d R;
  R << c, 0, s, 0, 1, 0, -s, 0, c;
  return R;
}

Projection Turntable::projection(int i) const {
  return pinhole_projection(K, rotation_about_axis(angle(i)), Eigen::Vector3d(0, 0, distance_mm));
}

std::vector<View> Turntable::all_views() const {
  std::vector<View> v;
  for (int i = 0; i < views; ++i) v.push_back({projection(i), width, height});
  return v;
}

Projection parallel_projection(double scale_px_per_mm, double cx, double cy, const Eigen::Matrix3d& R) {
  Projection P = Projection::Zero();
  P.block<2, 3>(0, 0) = scale_px_per_mm * R.topRows<2>();
  P(0, 3) = cx;
  P(1, 3) = cy;
  P(2, 3) = 1;
  return P;
}

Projection ParallelTurntable::projection(int i) const {
  return parallel_projection(scale_px_per_mm, cx, cy, rotation_about_axis(first_angle + step * i));
}

std::vector<View> ParallelTurntable::all_views() const {
  std::vector<View> v;
  for (int i = 0; i < views; ++i) v.push_back({projection(i), width, height});
  return v;
}

std::vector<Projection> read_projection_file(const std::filesystem::path& file, int expected) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("cannot read projection file '{}'", file.string()));
  std::vector<double> numbers;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      std::size_t used = 0;
      double value = 0;
      try {
        value = std::stod(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size() || !std::isfinite(value))
        throw InputError(
            fmt::format("{}:{}: '{}' is not a number; a projection file holds 12 numbers per view "
                        "(the 3x4 matrix row by row)",
                        file.string(), line_no, word));
      numbers.push_back(value);
    }
  }
  if (numbers.size() % 12 != 0)
    throw InputError(
        fmt::format("projection file '{}' holds {} numbers, not a multiple of 12 (one 3x4 matrix "
                    "per view, row by row)",
                    file.string(), numbers.size()));
  const int count = static_cast<int>(numbers.size() / 12);
  if (expected > 0 && count != expected)
    throw InputError(
        fmt::format("projection file '{}' holds {} matrices but there are {} images; give one "
                    "matrix per image, in the images' order",
                    file.string(), count, expected));
  std::vector<Projection> out(count);
  for (int v = 0; v < count; ++v)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) out[v](r, c) = numbers[12 * v + 4 * r + c];
  return out;
}

}  // namespace suite::carving
