// Tests of the thresholds between dish, gel and kernel on images whose levels are known.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "rice/measure/dish_levels.hpp"

namespace suite::rice {
namespace {

// A dish of level 20 with noise 3, a gel disc and a kernel ellipse inside it (levels given; a level
// of 0 leaves the shape out), blurred by 1.2 pixels like the optics.
cv::Mat dish_image(double gel, double kernel) {
  cv::Mat image(600, 800, CV_32F, cv::Scalar(20));
  if (gel > 0) cv::circle(image, {400, 300}, 200, cv::Scalar(gel), cv::FILLED);
  if (kernel > 0) cv::ellipse(image, {{400, 300}, {220, 90}, 30}, cv::Scalar(kernel), cv::FILLED);
  cv::GaussianBlur(image, image, cv::Size(), 1.2);
  cv::Mat noise(image.size(), CV_32F);
  cv::RNG(5).fill(noise, cv::RNG::NORMAL, 0.0, 3.0);
  image += noise;
  cv::Mat grey;
  image.convertTo(grey, CV_8U);
  return grey;
}

TEST(DishLevels, ThresholdsLieHalfWayBetweenThePopulations) {
  // The medians of flat noisy plateaus are their levels to within a grey level (integer histogram
  // bins and noise 3 over thousands of pixels); the thresholds are their midpoints. The noise is
  // 1.4826 x a whole number of grey levels (the median absolute deviation of integer levels: 2 or 3
  // for sigma 3 after rounding), so within 1.5.
  const DishLevels L = dish_levels(dish_image(100, 220));
  EXPECT_EQ(L.populations, "gel and kernel");
  EXPECT_NEAR(L.dish, 20, 1);
  EXPECT_NEAR(L.noise, 3, 1.5);
  EXPECT_NEAR(L.gel, 100, 1);
  EXPECT_NEAR(L.kernel, 220, 1);
  EXPECT_NEAR(L.grain_threshold, 60, 1);
  EXPECT_NEAR(L.kernel_threshold, 160, 1);
}

TEST(DishLevels, OnePopulationIsKernelOrGelByItsBrightness) {
  // Kernels alone: their blurred edges are no gel population (they are not flat).
  const DishLevels kernels = dish_levels(dish_image(0, 210));
  EXPECT_EQ(kernels.populations, "kernel");
  EXPECT_NEAR(kernels.kernel_threshold, 115, 1.5);
  EXPECT_EQ(kernels.kernel_threshold, kernels.grain_threshold);
  const DishLevels gel = dish_levels(dish_image(90, 0));
  EXPECT_EQ(gel.populations, "gel");
  EXPECT_EQ(gel.kernel_threshold, 256);
  EXPECT_NEAR(gel.grain_threshold, 55, 1.5);
  EXPECT_EQ(dish_levels(dish_image(0, 0)).populations, "none");
}

}  // namespace
}  // namespace suite::rice
