#pragma once
// Grain traits drawn at random around what `riceasv measure` finds for each grade (docs/rice.md,
// "Accuracy": gel/kernel ratio 0, 0.3, 1.2, 1.9, 10 from grade 2 to 6, kernel share from 1 to 0,
// split kernels of grade 5, no kernel for grade 7), for testing the classifier without images.
#include <limits>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "rice/classify/asv_classes.hpp"
#include "rice/classify/trait_features.hpp"
#include "rice/measure/grain_traits.hpp"

namespace suite::rice::testdata {

inline GrainTraits traits_of_grade(int grade, std::mt19937_64& rng) {
  auto u = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  GrainTraits t;
  t.kernel_area_mm2 = u(9, 14);
  t.kernel_pieces = 1;
  t.kernel_solidity = u(0.98, 1.0);
  t.kernel_length_mm = u(5.5, 7.5);
  t.kernel_width_mm = u(2.0, 2.8);
  const double ratio[] = {0, u(0.15, 0.45), u(0.9, 1.3), u(1.4, 2.3), u(4, 16)};
  const double share[] = {1, u(0.85, 0.95), u(0.64, 0.73), u(0.58, 0.68), u(0.15, 0.35)};
  if (grade <= 6) {
    t.gel_kernel_ratio = ratio[grade - 2];
    t.kernel_share = share[grade - 2];
  }
  t.collar_completeness = grade == 2 ? 0 : grade == 3 ? u(0.3, 1.0) : 1;
  if (grade == 5) t.kernel_pieces = static_cast<int>(u(2, 4.99)), t.kernel_solidity = u(0.92, 0.98);
  if (grade == 6) t.kernel_area_mm2 = u(3, 8), t.kernel_length_mm = u(2.5, 4.5);
  if (grade == 7) {
    t.kernel_area_mm2 = 0, t.kernel_pieces = 0, t.kernel_length_mm = 0, t.kernel_width_mm = 0;
    t.kernel_solidity = t.gel_kernel_ratio = std::numeric_limits<double>::quiet_NaN();
    t.kernel_share = 0;
    t.gel_area_mm2 = u(40, 70);
  } else {
    t.gel_area_mm2 = t.gel_kernel_ratio * t.kernel_area_mm2;
  }
  t.grain_area_mm2 = t.kernel_area_mm2 + t.gel_area_mm2;
  return t;
}

struct Samples {
  cv::Mat features;         // CV_32F, one row per grain
  std::vector<int> grades;  // 2..7
  std::vector<int> labels;  // class indices of `classes`
};

// `per_grade` grains of every grade 2..7, in grade order, from `seed`.
inline Samples samples(int per_grade, std::uint64_t seed, const AsvClasses& classes = AsvClasses::three()) {
  std::mt19937_64 rng(seed);
  Samples s;
  for (int grade = 2; grade <= 7; ++grade)
    for (int i = 0; i < per_grade; ++i) {
      s.features.push_back(features_of(traits_of_grade(grade, rng)));
      s.grades.push_back(grade);
      s.labels.push_back(classes.class_of(grade));
    }
  return s;
}

}  // namespace suite::rice::testdata
