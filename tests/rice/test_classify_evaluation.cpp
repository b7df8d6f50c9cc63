// The classifier's bookkeeping: the classes, the features (grade 7's missing kernel), the confusion
// matrix, the seeded split and the folds, and training with its evaluation on traits drawn per grade.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "rice/classify/asv_classes.hpp"
#include "rice/classify/evaluation.hpp"
#include "rice/classify/train_evaluate.hpp"
#include "rice/classify/trait_features.hpp"
#include "tests/rice/classify_test_data.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::rice {
namespace {

TEST(AsvClasses, ThreeClassesAndSixGrades) {
  const auto three = AsvClasses::three();
  const std::vector<int> expected = {0, 0, 1, 1, 2, 2};  // low 2-3, medium 4-5, high 6-7
  for (int grade = 2; grade <= 7; ++grade) {
    EXPECT_EQ(three.class_of(grade), expected[static_cast<std::size_t>(grade - 2)]) << grade;
    EXPECT_EQ(AsvClasses::grades().class_of(grade), grade - 2);
  }
  EXPECT_EQ(three.grades_of(1), "4-5");
  EXPECT_EQ(AsvClasses::grades().names.size(), 6u);
  EXPECT_NE(testing::input_error_of([] { AsvClasses::parse("five"); }).find("--classes 'five'"), std::string::npos);
  EXPECT_NE(testing::input_error_of([&] { three.class_of(8); }).find("grade 8 is not on the scale"), std::string::npos);
}

TEST(TraitFeatures, AMissingKernelTakesTheCapNotNaN) {
  std::mt19937_64 rng(3);
  const cv::Mat seven = features_of(testdata::traits_of_grade(7, rng));
  ASSERT_EQ(seven.cols, static_cast<int>(feature_names().size()));
  EXPECT_TRUE(cv::checkRange(seven));  // every entry finite
  auto at = [&](const cv::Mat& row, const std::string& name) {
    const auto& n = feature_names();
    return row.at<float>(0, static_cast<int>(std::find(n.begin(), n.end(), name) - n.begin()));
  };
  EXPECT_FLOAT_EQ(at(seven, "gel_kernel_ratio_log"), static_cast<float>(std::log1p(kRatioCap)));
  EXPECT_EQ(at(seven, "has_kernel"), 0.f);
  EXPECT_EQ(at(seven, "kernel_solidity"), 0.f);
  GrainTraits four = testdata::traits_of_grade(4, rng);
  four.gel_kernel_ratio = 1;
  EXPECT_FLOAT_EQ(at(features_of(four), "gel_kernel_ratio_log"), static_cast<float>(std::log(2.0)));
  EXPECT_EQ(at(features_of(four), "has_kernel"), 1.f);
  four.gel_kernel_ratio = 1e6;  // a speck of kernel in a cloud: no higher than no kernel at all
  EXPECT_FLOAT_EQ(at(features_of(four), "gel_kernel_ratio_log"), at(seven, "gel_kernel_ratio_log"));
}

TEST(Confusion, CountsAccuraciesAndTable) {
  Confusion c({"low", "medium", "high"});
  c.add(0, 0), c.add(0, 0), c.add(0, 1), c.add(1, 1), c.add(2, 1);
  EXPECT_EQ(c.total(), 5);
  EXPECT_DOUBLE_EQ(c.accuracy(), 3.0 / 5);
  const auto a = c.class_accuracy();
  EXPECT_DOUBLE_EQ(a[0], 2.0 / 3);
  EXPECT_DOUBLE_EQ(a[1], 1.0);
  EXPECT_DOUBLE_EQ(a[2], 0.0);
  EXPECT_EQ(c.to_csv(), "true \\ predicted,low,medium,high\nlow,2,1,0\nmedium,0,1,0\nhigh,0,1,0\n");
  EXPECT_TRUE(std::isnan(Confusion({"a", "b"}).class_accuracy()[0]));
  EXPECT_TRUE(c.to_json()["per_class"]["high"]["accuracy"] == 0.0);
}

TEST(Split, SeededStratifiedAndComplete) {
  std::vector<int> labels;
  for (int c = 0; c < 3; ++c) labels.insert(labels.end(), 16, c);  // 16 per class: 12 / 2 / 2
  const Split s = stratified_split(labels, 0.125, 0.125, 7);
  EXPECT_EQ(s.train.size(), 36u);
  EXPECT_EQ(s.validation.size(), 6u);
  EXPECT_EQ(s.test.size(), 6u);
  std::set<int> all(s.train.begin(), s.train.end());
  all.insert(s.validation.begin(), s.validation.end());
  all.insert(s.test.begin(), s.test.end());
  EXPECT_EQ(all.size(), labels.size());  // disjoint and complete
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(
        std::count_if(s.test.begin(), s.test.end(), [&](int i) { return labels[static_cast<std::size_t>(i)] == c; }),
        2);
  EXPECT_EQ(stratified_split(labels, 0.125, 0.125, 7).test, s.test);
  EXPECT_NE(stratified_split(labels, 0.125, 0.125, 8).test, s.test);
  EXPECT_TRUE(stratified_split(labels, 0, 0.25, 1).validation.empty());
  EXPECT_NE(testing::input_error_of([&] { stratified_split(labels, 0.5, 0.5, 1); }).find("--validation-share"),
            std::string::npos);
}

TEST(Split, FoldsCoverEveryGrainOnce) {
  std::vector<int> labels;
  for (int c = 0; c < 3; ++c) labels.insert(labels.end(), 11 + c, c);
  const auto fold = stratified_folds(labels, 5, 1);
  ASSERT_EQ(fold.size(), labels.size());
  std::vector<int> sizes(5, 0);
  for (int f : fold) {
    ASSERT_TRUE(f >= 0 && f < 5);
    ++sizes[static_cast<std::size_t>(f)];
  }
  EXPECT_LE(*std::max_element(sizes.begin(), sizes.end()) - *std::min_element(sizes.begin(), sizes.end()), 1);
  EXPECT_NE(testing::input_error_of([&] { stratified_folds(labels, 1, 1); }).find("--folds 1"), std::string::npos);
  EXPECT_NE(testing::input_error_of([&] { stratified_folds({0, 1}, 3, 1); }).find("--folds 3"), std::string::npos);
}

TEST(TrainEvaluate, KFoldGivesKResultsAndMatricesSumToTheGrains) {
  const auto data = testdata::samples(16, 21);
  TrainOptions o;
  o.folds = 4;
  const Evaluation e = train_and_evaluate(data.features, data.labels, o);
  EXPECT_EQ(e.fold_accuracy.size(), 4u);
  EXPECT_EQ(e.cross_validation.total(), data.features.rows);  // every grain predicted once
  EXPECT_EQ(e.test.total(), static_cast<long>(e.split.test.size()));
  EXPECT_EQ(e.split.train.size() + e.split.validation.size() + e.split.test.size(),
            static_cast<std::size_t>(data.features.rows));
  EXPECT_EQ(e.selection["tried"].size(), 3u);  // depths 4, 8, 16 on the validation grains
  // The drawn grades are apart in ratio, completeness and share as the measured ones are, so the
  // folds should classify them all but a few (ranges of grades 3/4 and 5/6 touch at the edges).
  EXPECT_GT(e.cross_validation.accuracy(), 0.95);
  const double mean = std::accumulate(e.fold_accuracy.begin(), e.fold_accuracy.end(), 0.0) / 4;
  EXPECT_GT(mean, 0.9);
}

TEST(TrainEvaluate, AClassWithoutGrainsIsNamed) {
  auto data = testdata::samples(6, 5);
  std::vector<int> rows;  // drop grades 6 and 7: no "high" grain
  for (int i = 0; i < data.features.rows; ++i)
    if (data.grades[static_cast<std::size_t>(i)] < 6) rows.push_back(i);
  std::vector<int> labels;
  for (int r : rows) labels.push_back(data.labels[static_cast<std::size_t>(r)]);
  const std::string message =
      testing::input_error_of([&] { train_and_evaluate(select_rows(data.features, rows), labels, TrainOptions{}); });
  EXPECT_NE(message.find("class 'high' (grade 6-7) has no usable grain"), std::string::npos) << message;
}

}  // namespace
}  // namespace suite::rice
