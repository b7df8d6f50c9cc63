#pragma once
// The classes a classifier of the alkali spreading value predicts (docs/rice.md, "The classifier"):
//   three   low (grades 2-3), medium (4-5), high (6-7), the classification of the dissertation's
//           section 4.3 (the grades a breeder acts on: low ASV = high gelatinisation temperature);
//   grades  the six grades 2..7 themselves.
// A class is an index 0, 1, ... into `names`; OpenCV's models see these indices as labels.
#include <string>
#include <vector>

namespace suite::rice {

struct AsvClasses {
  std::string scheme;              // "three" or "grades"
  std::vector<std::string> names;  // class index -> name ("low", ... or "2", ...)

  static AsvClasses three();
  static AsvClasses grades();
  // "three" or "grades"; InputError naming --classes and what is valid otherwise.
  static AsvClasses parse(const std::string& scheme);

  int count() const { return static_cast<int>(names.size()); }
  // The class of a grade 2..7; InputError for a grade off the scale.
  int class_of(int grade) const;
  // The grades a class holds, e.g. "2-3" or "5", for messages and reports.
  std::string grades_of(int label) const;
};

}  // namespace suite::rice
