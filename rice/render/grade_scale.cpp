#include "rice/render/grade_scale.hpp"

#include <fmt/format.h>

#include <array>

#include "core/errors.hpp"

namespace suite::rice {
namespace {

std::array<GradeAppearance, 6> make_scale() {
  std::array<GradeAppearance, 6> s{};
  // grade, words, swelling, collar width, completeness, narrow share, narrow width, pieces, cracks,
  // remnant scale, remnant level, cloud radius
  s[0] = {2,     "kernel swollen, not spread", {1.00, 1.08}, {0, 0}, {0, 0}, 0, {0, 0}, 1, 1, {0, 0}, {0, 0}, {0, 0},
          {0, 0}};
  s[1] = {3,
          "kernel swollen, collar incomplete or narrow",
          {1.04, 1.10},
          {0.30, 0.55},
          {0.35, 0.80},
          0.4,
          {0.22, 0.32},
          1,
          1,
          {0, 0},
          {0, 0},
          {0, 0},
          {0, 0}};
  s[2] = {4,
          "kernel swollen, collar complete and wide",
          {1.06, 1.12},
          {0.70, 1.05},
          {1, 1},
          0,
          {0, 0},
          1,
          1,
          {0, 0},
          {0, 0},
          {0, 0},
          {0, 0}};
  s[3] = {5,
          "kernel split or segmented, collar complete and wide",
          {1.06, 1.12},
          {0.95, 1.35},
          {1, 1},
          0,
          {0, 0},
          2,
          4,
          {0.10, 0.20},
          {0, 0},
          {0, 0},
          {0, 0}};
  s[4] = {6,
          "kernel dispersed, merging with the collar",
          {1.06, 1.12},
          {1.40, 2.00},
          {1, 1},
          0,
          {0, 0},
          1,
          1,
          {0, 0},
          {0.40, 0.65},
          {0.70, 0.80},
          {0, 0}};
  s[5] = {7,
          "kernel completely dispersed and intermingled",
          {1.06, 1.12},
          {0, 0},
          {1, 1},
          0,
          {0, 0},
          0,
          0,
          {0, 0},
          {0, 0},
          {0, 0},
          {1.6, 2.4}};
  return s;
}

}  // namespace

const GradeAppearance& appearance(int grade) {
  static const std::array<GradeAppearance, 6> scale = make_scale();
  if (grade < kLowestGrade || grade > kHighestGrade)
    throw InputError(
        fmt::format("alkali spreading value {} is not on the scale; grades are whole numbers from {} to {}", grade,
                    kLowestGrade, kHighestGrade));
  return scale[static_cast<std::size_t>(grade - kLowestGrade)];
}

}  // namespace suite::rice
