#pragma once
// How well a classifier does, and the seeded partitions it is judged on (docs/rice.md, "Training"):
//   Confusion       counts[true class][predicted class]; overall accuracy (the diagonal over the
//                   total) and per-class accuracy (the diagonal over the row: the share of a class's
//                   grains called right, NaN for a class with no grains);
//   stratified_split   each class's grains shuffled with the seed and cut into train, validation and
//                   test shares (the dissertation's 75 / 12.5 / 12.5%), so every class is in each
//                   part in proportion;
//   stratified_folds   each grain's fold 0..k-1 for k-fold cross-validation, classes dealt round the
//                   folds so every fold holds about 1/k of each class.
// The shuffles use their own Fisher-Yates on std::mt19937_64, so a seed gives the same partition with
// every standard library. Not collective.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace suite::rice {

struct Confusion {
  std::vector<std::string> classes;
  std::vector<std::vector<long>> counts;  // [true][predicted]

  explicit Confusion(std::vector<std::string> class_names = {});
  void add(int truth, int predicted);
  void add(const Confusion& other);
  long total() const;
  double accuracy() const;                     // NaN when empty
  std::vector<double> class_accuracy() const;  // NaN for a class with no grains
  nlohmann::json to_json() const;
  // "true \\ predicted,low,medium,high" then one row per true class.
  std::string to_csv() const;
};

struct Split {
  std::vector<int> train, validation, test;  // indices into the labels
};

// InputError unless the shares are in [0, 1) and leave a training share.
Split stratified_split(const std::vector<int>& labels, double validation_share, double test_share, std::uint64_t seed);

// The fold (0..k-1) of each label's grain; InputError unless 2 <= k <= labels.size().
std::vector<int> stratified_folds(const std::vector<int>& labels, int k, std::uint64_t seed);

}  // namespace suite::rice
