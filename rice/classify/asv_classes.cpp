#include "rice/classify/asv_classes.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "rice/render/grade_scale.hpp"

namespace suite::rice {

AsvClasses AsvClasses::three() {
  return {"three", {"low", "medium", "high"}};
}

AsvClasses AsvClasses::grades() {
  AsvClasses c{"grades", {}};
  for (int g = kLowestGrade; g <= kHighestGrade; ++g) c.names.push_back(std::to_string(g));
  return c;
}

AsvClasses AsvClasses::parse(const std::string& scheme) {
  if (scheme == "three") return three();
  if (scheme == "grades") return grades();
  throw InputError(fmt::format(
      "--classes '{}': give 'three' (low 2-3, medium 4-5, high 6-7) or 'grades' (the six grades 2-7)", scheme));
}

int AsvClasses::class_of(int grade) const {
  if (grade < kLowestGrade || grade > kHighestGrade)
    throw InputError(
        fmt::format("grade {} is not on the scale; grades go from {} to {}", grade, kLowestGrade, kHighestGrade));
  return scheme == "three" ? (grade - kLowestGrade) / 2 : grade - kLowestGrade;
}

std::string AsvClasses::grades_of(int label) const {
  if (scheme == "three") return fmt::format("{}-{}", kLowestGrade + 2 * label, kLowestGrade + 2 * label + 1);
  return std::to_string(kLowestGrade + label);
}

}  // namespace suite::rice
