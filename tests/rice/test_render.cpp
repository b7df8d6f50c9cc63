// Tests of the synthetic renderer of grains in alkali: the scale, the collar's angular coverage,
// the drawn kernel against the analytic superellipse, the pieces of a split kernel, determinism,
// and grains drawn with a neighbouring grade's appearance (--blend).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <random>

#include "core/errors.hpp"
#include "core/mpi/comm.hpp"
#include "rice/render/dish_renderer.hpp"
#include "rice/render/grade_scale.hpp"
#include "rice/render/grain_shape.hpp"
#include "rice/render/render_set.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::rice {
namespace {

TEST(GradeScale, OnlyGradesTwoToSevenAreDrawn) {
  EXPECT_EQ(appearance(5).description, "kernel split or segmented, collar complete and wide");
  EXPECT_NE(testing::input_error_of([] { appearance(8); }).find("grades are whole numbers from 2 to 7"),
            std::string::npos);
  EXPECT_EQ(parse_grades("2,4,7"), (std::vector<int>{2, 4, 7}));
  EXPECT_NE(testing::input_error_of([] { parse_grades("2,9"); }).find("--grades '2,9': 9 is not on the scale"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([] { parse_grades("2,x"); }).find("'x' is not a whole number"), std::string::npos);
  EXPECT_NE(testing::input_error_of([] { parse_grades("3,3"); }).find("3 is given twice"), std::string::npos);
}

TEST(GrainShape, SectorCoverageIsThePolarAngleSwept) {
  // A circle: parametric and polar angles agree, so the coverage is span / 360 (to the 0.05 degree
  // summation step's round-off). An ellipse's quadrant covers a quarter of the directions by symmetry,
  // while 45 parametric degrees from its long axis cover less than an eighth (the point lies nearer
  // the long axis than the parameter).
  EXPECT_NEAR(sector_coverage(100, 100, 30, 90), 0.25, 1e-9);
  EXPECT_NEAR(sector_coverage(100, 100, 200, 270), 0.75, 1e-9);
  EXPECT_NEAR(sector_coverage(300, 100, 0, 90), 0.25, 1e-9);
  EXPECT_NEAR(sector_coverage(300, 100, 90, 180), 0.5, 1e-9);
  EXPECT_LT(sector_coverage(300, 100, 0, 45), 0.125);
  EXPECT_EQ(sector_coverage(300, 100, 0, 360), 1);
}

TEST(GrainShape, DrawnKernelHasTheSuperellipseArea) {
  // Area of |x/a|^n + |y/b|^n <= 1: 4 a b Gamma(1 + 1/n)^2 / Gamma(1 + 2/n). fillPoly marks every
  // pixel the outline encloses or touches, so the count exceeds the exact area by less than one
  // pixel along the perimeter: 0 <= error < perimeter / area (in pixels; about 2.5% for a
  // 6.5 x 2.2 mm kernel at 0.02 mm, and the drawn grains come out +1.3 to +1.4%). A pixel size
  // applied twice or not at all would be off by factors of 50.
  const double n = kRiceExponent, mm_per_px = 0.02;
  std::mt19937_64 rng(7);
  for (int k = 0; k < 5; ++k) {
    GrainSpec s = random_grain(2, {500.3, 400.7}, rng);
    const GrainLayers L = draw_grain(s, mm_per_px);
    const GrainTruth t = grain_truth(s, L, mm_per_px, 18);
    const double a = 0.5 * s.length_mm, b = 0.5 * s.width_mm;
    const double exact = 4 * a * b * std::pow(std::tgamma(1 + 1 / n), 2) / std::tgamma(1 + 2 / n);
    std::vector<cv::Point2f> outline;
    for (const auto& p : superellipse_outline({0, 0}, a / mm_per_px, b / mm_per_px, 0)) outline.emplace_back(p);
    const double perimeter_px = cv::arcLength(outline, true);
    const double error = t.kernel_area_mm2 / exact - 1;
    EXPECT_GE(error, 0) << "grain " << k;
    EXPECT_LT(error, perimeter_px / (exact / (mm_per_px * mm_per_px))) << "grain " << k;
    EXPECT_EQ(t.gel_area_mm2, 0);
    EXPECT_EQ(t.kernel_pieces, 1);
    EXPECT_EQ(t.kernel_share, 1);
  }
}

TEST(GrainShape, SplitKernelHasAsManyPiecesAsTheTruthSays) {
  // The truth counts cracks + 1; the drawn mask must agree (each crack crosses the whole kernel).
  std::mt19937_64 rng(11);
  for (int k = 0; k < 12; ++k) {
    const GrainSpec s = random_grain(5, {400, 400}, rng);
    const GrainLayers L = draw_grain(s, 0.02);
    const GrainTruth t = grain_truth(s, L, 0.02, 18);
    cv::Mat labels;
    EXPECT_EQ(cv::connectedComponents(L.kernel, labels, 8) - 1, t.kernel_pieces) << "grain " << k;
    EXPECT_GE(t.kernel_pieces, 2);
    EXPECT_EQ(t.collar_completeness, 1);
  }
  const GrainSpec cloud = random_grain(7, {400, 400}, rng);
  const GrainTruth t = grain_truth(cloud, draw_grain(cloud, 0.02), 0.02, 18);
  EXPECT_EQ(t.kernel_area_mm2, 0);
  EXPECT_EQ(t.kernel_pieces, 0);
  EXPECT_TRUE(std::isnan(t.gel_kernel_ratio));
  EXPECT_GT(t.gel_area_mm2, 20);
}

TEST(DishRenderer, SameSeedSameImage) {
  DishOptions o;
  o.mm_per_px = 0.04;
  std::mt19937_64 a(3), b(3), c(4);
  const cv::Mat first = render_dish({2, 4, 6}, o, a).image, second = render_dish({2, 4, 6}, o, b).image;
  const cv::Mat other = render_dish({2, 4, 6}, o, c).image;
  EXPECT_EQ(cv::norm(first, second, cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(first, other, cv::NORM_INF), 0);
  EXPECT_EQ(first.cols, 3 * static_cast<int>(std::lround(o.cell_mm / o.mm_per_px)));
  EXPECT_NE(image_seed(1, 2, 1), image_seed(1, 3, 1));
}

TEST(DishRenderer, BadOptionsNameTheOption) {
  DishOptions o;
  o.mm_per_px = 0.5;
  std::mt19937_64 rng(1);
  EXPECT_NE(testing::input_error_of([&] { render_dish({2}, o, rng); }).find("pixel size 0.5 mm is outside"),
            std::string::npos);
}

TEST(RenderSet, BlendDrawsNeighbouringGradesAtTheGivenShare) {
  // 120 grains per grade at 0.1 mm per pixel (small photographs). Each grain looks like its own
  // grade or a neighbour; the share drawn otherwise is P (grade 2 and 7: P/2, one neighbour each
  // drawn with P/2), within 4 binomial standard deviations; labels stay the photograph's grade.
  const auto dir = testing::scratch_dir(mpi::Comm(MPI_COMM_SELF)) / "blend";
  RenderSetOptions o;
  o.per_grade = 120;
  o.seed = 4;
  o.blend = 0.4;
  o.dish.mm_per_px = 0.1;
  const auto set = render_set(o, dir);
  std::map<int, std::pair<int, int>> moved;  // grade -> (drawn otherwise, grains)
  for (const auto& row : set.truth) {
    const int drawn = row.grain.spec.grade;
    EXPECT_EQ(std::to_string(row.grade), row.image.substr(3, 1));  // asv<grade>_<k>.png
    EXPECT_LE(std::abs(drawn - row.grade), 1) << row.image;
    moved[row.grade].first += drawn != row.grade;
    moved[row.grade].second += 1;
  }
  for (const auto& [grade, counts] : moved) {
    const double p = grade == 2 || grade == 7 ? o.blend / 2 : o.blend, n = counts.second;
    EXPECT_NEAR(counts.first / n, p, 4 * std::sqrt(p * (1 - p) / n)) << "grade " << grade;
  }
  // Three classes: grades 3, 4, 5 and 6 lose P/2 across a class boundary, 2 and 7 none: 1 - P/3.
  // Six grades: every draw of a neighbour crosses: 1 - (2 P/2 + 4 P) / 6 = 1 - 5P/6.
  EXPECT_NEAR(blend_ceiling(o.grades, 0.3, {0, 0, 1, 1, 2, 2}), 0.9, 1e-12);
  EXPECT_NEAR(blend_ceiling(o.grades, 0.3, {0, 1, 2, 3, 4, 5}), 0.75, 1e-12);
  EXPECT_NE(testing::input_error_of([&] {
              RenderSetOptions bad = o;
              bad.blend = 1.5;
              render_set(bad, dir);
            }).find("--blend 1.5"),
            std::string::npos);
}

}  // namespace
}  // namespace suite::rice
