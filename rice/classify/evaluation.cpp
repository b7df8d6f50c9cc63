#include "rice/classify/evaluation.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "core/errors.hpp"

namespace suite::rice {
namespace {

// Each class's indices in a seeded random order (classes in ascending label order).
std::map<int, std::vector<int>> shuffled_by_class(const std::vector<int>& labels, std::uint64_t seed) {
  std::map<int, std::vector<int>> by_class;
  for (int i = 0; i < static_cast<int>(labels.size()); ++i) by_class[labels[static_cast<std::size_t>(i)]].push_back(i);
  std::mt19937_64 rng(seed);
  for (auto& [label, indices] : by_class)
    for (std::size_t i = indices.size(); i > 1; --i) std::swap(indices[i - 1], indices[rng() % i]);
  return by_class;
}

}  // namespace

Confusion::Confusion(std::vector<std::string> class_names)
    : classes(std::move(class_names)), counts(classes.size(), std::vector<long>(classes.size(), 0)) {}

void Confusion::add(int truth, int predicted) {
  counts.at(static_cast<std::size_t>(truth)).at(static_cast<std::size_t>(predicted)) += 1;
}

void Confusion::add(const Confusion& other) {
  for (std::size_t t = 0; t < counts.size(); ++t)
    for (std::size_t p = 0; p < counts.size(); ++p) counts[t][p] += other.counts.at(t).at(p);
}

long Confusion::total() const {
  long n = 0;
  for (const auto& row : counts)
    for (long c : row) n += c;
  return n;
}

double Confusion::accuracy() const {
  long right = 0;
  for (std::size_t c = 0; c < counts.size(); ++c) right += counts[c][c];
  const long n = total();
  return n > 0 ? static_cast<double>(right) / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

std::vector<double> Confusion::class_accuracy() const {
  std::vector<double> a;
  for (std::size_t c = 0; c < counts.size(); ++c) {
    long row = 0;
    for (long n : counts[c]) row += n;
    a.push_back(row > 0 ? static_cast<double>(counts[c][c]) / static_cast<double>(row)
                        : std::numeric_limits<double>::quiet_NaN());
  }
  return a;
}

nlohmann::json Confusion::to_json() const {
  auto finite = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  nlohmann::json per_class = nlohmann::json::object();
  const auto a = class_accuracy();
  for (std::size_t c = 0; c < classes.size(); ++c) {
    long row = 0;
    for (long n : counts[c]) row += n;
    per_class[classes[c]] = {{"accuracy", finite(a[c])}, {"grains", row}};
  }
  return {{"grains", total()},
          {"accuracy", finite(accuracy())},
          {"per_class", per_class},
          {"classes", classes},
          {"confusion", counts},
          {"confusion_layout", "rows: true class, columns: predicted class, in the order of 'classes'"}};
}

std::string Confusion::to_csv() const {
  std::string text = "true \\ predicted";
  for (const auto& c : classes) text += "," + c;
  text += "\n";
  for (std::size_t t = 0; t < classes.size(); ++t) {
    text += classes[t];
    for (long n : counts[t]) text += fmt::format(",{}", n);
    text += "\n";
  }
  return text;
}

Split stratified_split(const std::vector<int>& labels, double validation_share, double test_share, std::uint64_t seed) {
  if (!(validation_share >= 0 && test_share >= 0 && validation_share + test_share < 1))
    throw InputError(fmt::format(
        "--validation-share {} and --test-share {}: give shares in [0, 1) that leave some grains to train on "
        "(e.g. 0.125 and 0.125)",
        validation_share, test_share));
  Split split;
  for (const auto& [label, indices] : shuffled_by_class(labels, seed)) {
    const auto n = static_cast<long>(indices.size());
    // Round each share, but keep at least one grain of the class for training.
    long n_test = std::min(std::lround(test_share * static_cast<double>(n)), n - 1);
    long n_validation = std::min(std::lround(validation_share * static_cast<double>(n)), n - 1 - n_test);
    for (long i = 0; i < n; ++i) {
      const int index = indices[static_cast<std::size_t>(i)];
      if (i < n_test)
        split.test.push_back(index);
      else if (i < n_test + n_validation)
        split.validation.push_back(index);
      else
        split.train.push_back(index);
    }
  }
  return split;
}

std::vector<int> stratified_folds(const std::vector<int>& labels, int k, std::uint64_t seed) {
  if (k < 2 || k > static_cast<int>(labels.size()))
    throw InputError(
        fmt::format("--folds {}: give from 2 to the number of usable grains ({}), e.g. 5", k, labels.size()));
  std::vector<int> fold(labels.size(), 0);
  int next = 0;  // carried from class to class, so that small classes do not all start at fold 0
  for (const auto& [label, indices] : shuffled_by_class(labels, seed))
    for (int index : indices) fold[static_cast<std::size_t>(index)] = next++ % k;
  return fold;
}

}  // namespace suite::rice
