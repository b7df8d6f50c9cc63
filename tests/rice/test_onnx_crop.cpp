// The ONNX path's input rules (rice/classify/onnx_classifier.hpp): net.json's keys are checked with
// messages naming the key, and the crop is the square of crop_mm / pixel size pixels centred on the
// grain, the dish level outside the photograph, area-averaged to the input size, in the network's
// colour order. The network itself is tested end to end (tests/rice/CMakeLists.txt, check_onnx.py).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "core/errors.hpp"
#include "rice/classify/onnx_classifier.hpp"

namespace {

using suite::rice::crop_for_network;
using suite::rice::OnnxSpec;
using suite::rice::parse_onnx_spec;

nlohmann::json good_spec() {
  return nlohmann::json::parse(R"({"format": "riceasv onnx classifier", "version": 1,
    "classes": ["low", "medium", "high"], "input": {"width": 10, "height": 10, "channels": 1},
    "crop_mm": 1.0, "normalisation": {"mean": [0.5], "std": [0.25]}, "output": "logits"})");
}

std::string error_of(const nlohmann::json& j) {
  try {
    parse_onnx_spec(j, "net.json");
  } catch (const suite::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OnnxSpec, ReadsTheConvention) {
  const OnnxSpec s = parse_onnx_spec(good_spec(), "net.json");
  EXPECT_EQ(s.classes.size(), 3u);
  EXPECT_EQ(s.width, 10);
  EXPECT_EQ(s.channels, 1);
  EXPECT_DOUBLE_EQ(s.crop_mm, 1.0);
  EXPECT_DOUBLE_EQ(s.std[0], 0.25);
  EXPECT_TRUE(s.logits);
}

TEST(OnnxSpec, EachMistakeNamesItsKey) {
  auto j = good_spec();
  j["format"] = "riceasv traits classifier";
  EXPECT_NE(error_of(j).find("is not a riceasv onnx classifier description"), std::string::npos) << error_of(j);
  j = good_spec();
  j["classes"] = {"low"};
  EXPECT_NE(error_of(j).find("'classes' must be a list of at least two names"), std::string::npos);
  j = good_spec();
  j["input"]["channels"] = 2;
  EXPECT_NE(error_of(j).find("'input.channels' must be 1"), std::string::npos);
  j = good_spec();
  j["normalisation"]["mean"] = {0.4, 0.5, 0.6};  // three means for one channel
  EXPECT_NE(error_of(j).find("'normalisation.mean' must be a list of 1 number"), std::string::npos);
  j = good_spec();
  j["normalisation"]["std"] = {0.0};
  EXPECT_NE(error_of(j).find("'normalisation.std' must be a list of 1 number(s) above 0"), std::string::npos);
  j = good_spec();
  j["crop_mm"] = -3;
  EXPECT_NE(error_of(j).find("'crop_mm' must be a number above 0"), std::string::npos);
  j = good_spec();
  j["croop_mm"] = 3;
  EXPECT_NE(error_of(j).find("unknown key 'croop_mm'"), std::string::npos);
  j = good_spec();
  j["output"] = "scores";
  EXPECT_NE(error_of(j).find("'output' is 'scores'"), std::string::npos);
}

TEST(OnnxCrop, CentredSquareAveragedToTheInput) {
  const OnnxSpec s = parse_onnx_spec(good_spec(), "net.json");
  // Pixel value = column (0..99): a 20-pixel crop (1 mm at 0.05 mm) from column 40 (round(50.2 - 10)),
  // averaged 2:1, gives the mean of columns 40 + 2k and 41 + 2k, 40.5 + 2k, within 8 bits' rounding.
  cv::Mat image(100, 100, CV_8UC1);
  for (int r = 0; r < 100; ++r)
    for (int c = 0; c < 100; ++c) image.at<unsigned char>(r, c) = static_cast<unsigned char>(c);
  cv::Rect region;
  const cv::Mat crop = crop_for_network(s, image, 50.2, 49.8, 0.05, 18, &region);
  EXPECT_EQ(region, cv::Rect(40, 40, 20, 20));
  ASSERT_EQ(crop.size(), cv::Size(10, 10));
  ASSERT_EQ(crop.type(), CV_8UC1);
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(crop.at<unsigned char>(5, k), 40 + 2 * k + 0.5, 0.5) << k;

  // At the corner: the part outside the photograph is the dish level.
  const cv::Mat corner = crop_for_network(s, image, 2, 2, 0.05, 18, &region);
  EXPECT_EQ(region, cv::Rect(-8, -8, 20, 20));
  EXPECT_EQ(corner.at<unsigned char>(0, 0), 18);
  EXPECT_EQ(corner.at<unsigned char>(9, 9), 11);  // mean of columns 10 and 11 (10.5), rounded
}

TEST(OnnxCrop, ColourOrderForThreeChannels) {
  auto j = good_spec();
  j["input"]["channels"] = 3;
  j["normalisation"] = {{"mean", {0.485, 0.456, 0.406}}, {"std", {0.229, 0.224, 0.225}}};
  OnnxSpec s = parse_onnx_spec(j, "net.json");
  const cv::Mat bgr(40, 40, CV_8UC3, cv::Scalar(10, 20, 30));  // OpenCV's order: blue 10, red 30
  cv::Mat crop = crop_for_network(s, bgr, 20, 20, 0.05, 18);
  EXPECT_EQ(crop.at<cv::Vec3b>(5, 5), cv::Vec3b(30, 20, 10));  // rgb (the default)
  j["input"]["colour_order"] = "bgr";
  s = parse_onnx_spec(j, "net.json");
  crop = crop_for_network(s, bgr, 20, 20, 0.05, 18);
  EXPECT_EQ(crop.at<cv::Vec3b>(5, 5), cv::Vec3b(10, 20, 30));
}

}  // namespace
