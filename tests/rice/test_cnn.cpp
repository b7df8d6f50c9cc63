// The convolutional network (rice/cnn/grain_cnn.hpp) on crops drawn here: three classes that look as
// the three ASV classes do in a crop (a bright kernel alone; a kernel in a grey collar; a grey cloud
// without a kernel), at random orientation, size and brightness, with sensor noise. A network that
// learns anything separates them, so it must classify more than 90% of crops drawn with another seed
// (the bound the issue sets for rendered grains). A seed and a thread count fix the weights bit for
// bit; a save/load round trip predicts the same probabilities; and a model folder whose files are not
// what `riceasv train --model-type cnn` writes says which file is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <random>

#include "core/errors.hpp"
#include "core/mpi/comm.hpp"
#include "rice/classify/trait_classifier.hpp"
#include "rice/cnn/grain_cnn.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::rice {
namespace {

constexpr int kSide = 32;

struct Crops {
  cv::Mat rows;  // CV_8U, one crop per row
  std::vector<int> labels;
};

// `per_class` crops of each class 0 (kernel), 1 (kernel and collar), 2 (cloud), drawn with `seed`.
Crops draw(int per_class, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Crops out;
  for (int label = 0; label < 3; ++label)
    for (int k = 0; k < per_class; ++k) {
      cv::Mat crop(kSide, kSide, CV_8U, cv::Scalar(25 + 10 * u(rng)));
      const cv::Point2f centre(kSide / 2.0f + static_cast<float>(4 * u(rng) - 2),
                               kSide / 2.0f + static_cast<float>(4 * u(rng) - 2));
      const float length = static_cast<float>(11 + 3 * u(rng)), width = static_cast<float>(4 + 1.5 * u(rng));
      const float angle = static_cast<float>(180 * u(rng));
      const double kernel = 190 + 40 * u(rng), gel = 90 + 30 * u(rng);
      if (label == 1)
        cv::ellipse(crop, cv::RotatedRect(centre, {length + 10, width + 10}, angle), cv::Scalar(gel), cv::FILLED);
      if (label == 2)
        cv::ellipse(crop, cv::RotatedRect(centre, {length + 12, length + 4}, angle), cv::Scalar(gel), cv::FILLED);
      else
        cv::ellipse(crop, cv::RotatedRect(centre, {length, width}, angle), cv::Scalar(kernel), cv::FILLED);
      cv::Mat noise(crop.size(), CV_16S);
      cv::randn(noise, 0, 6);
      crop.convertTo(crop, CV_16S);
      crop += noise;
      crop.convertTo(crop, CV_8U);
      out.rows.push_back(crop.reshape(1, 1));
      out.labels.push_back(label);
    }
  return out;
}

CnnOptions small_options() {
  CnnOptions o;
  o.input_px = kSide;
  o.epochs = 25;
  o.threads = 1;
  return o;
}

double accuracy(const std::vector<Prediction>& predicted, const std::vector<int>& labels) {
  int right = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) right += predicted[i].label == labels[i];
  return static_cast<double>(right) / static_cast<double>(labels.size());
}

TEST(GrainCnn, LearnsTheDrawnClassesAndClassifiesUnseenCrops) {
  const Crops train = draw(20, 1), unseen = draw(20, 2);
  const auto net = CnnClassifier::fit(train.rows, train.labels, AsvClasses::three(), small_options());
  const auto predicted = net.predict(unseen.rows);
  EXPECT_GT(accuracy(predicted, unseen.labels), 0.9);
  for (const auto& p : predicted) EXPECT_TRUE(p.share > 1.0 / 3 - 1e-12 && p.share <= 1.0) << p.share;
  const cv::Mat p = net.probabilities(unseen.rows);
  for (int i = 0; i < p.rows; ++i) EXPECT_NEAR(cv::sum(p.row(i))[0], 1.0, 1e-12);
}

TEST(GrainCnn, ASeedAndAThreadCountFixTheWeights) {
  const Crops train = draw(8, 3), unseen = draw(4, 4);
  CnnOptions o = small_options();
  o.epochs = 3;
  const cv::Mat a = CnnClassifier::fit(train.rows, train.labels, AsvClasses::three(), o).probabilities(unseen.rows);
  const cv::Mat b = CnnClassifier::fit(train.rows, train.labels, AsvClasses::three(), o).probabilities(unseen.rows);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  o.seed = 2;
  const cv::Mat c = CnnClassifier::fit(train.rows, train.labels, AsvClasses::three(), o).probabilities(unseen.rows);
  EXPECT_GT(cv::norm(a, c, cv::NORM_INF), 1e-6);
}

TEST(GrainCnn, SaveAndLoadPredictTheSame) {
  const auto dir = testing::scratch_dir(mpi::Comm(MPI_COMM_SELF)) / "cnn";
  const Crops train = draw(8, 5), unseen = draw(5, 6);
  CnnOptions o = small_options();
  o.epochs = 3;
  const auto net = CnnClassifier::fit(train.rows, train.labels, AsvClasses::three(), o);
  net.save(dir, {{"note", "test"}});
  EXPECT_TRUE(CnnClassifier::is_cnn_model(dir));
  const auto loaded = CnnClassifier::load(dir);
  EXPECT_EQ(cv::norm(net.probabilities(unseen.rows), loaded.probabilities(unseen.rows), cv::NORM_INF), 0.0);
  EXPECT_EQ(loaded.options().input_px, kSide);
  EXPECT_EQ(loaded.classes().names, AsvClasses::three().names);
  // 1x3x3x8+8, 2x8 (batch norm), 8x3x3x16+16, 2x16, 16x3x3x32+32, 2x32, 32x3+3 weights.
  EXPECT_EQ(net.description()["architecture"]["weights"].get<long>(), 80 + 16 + 1168 + 32 + 4640 + 64 + 99);
  // One crop as classify feeds it equals its row of the batch.
  const std::vector<double> one = loaded.scores(unseen.rows.row(2).clone().reshape(1, kSide));
  const cv::Mat batch = loaded.probabilities(unseen.rows);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(one[static_cast<std::size_t>(k)], batch.at<double>(2, k), 1e-6);
}

TEST(GrainCnn, AWrongModelFolderNamesTheFile) {
  const auto dir = testing::scratch_dir(mpi::Comm(MPI_COMM_SELF)) / "cnn_bad";
  const Crops train = draw(6, 7);
  CnnOptions o = small_options();
  o.epochs = 1;
  CnnClassifier::fit(train.rows, train.labels, AsvClasses::three(), o).save(dir, {});
  // Weights that are not an archive.
  std::ofstream(dir / "model.pt") << "not a libtorch archive";
  std::string message = testing::input_error_of([&] { CnnClassifier::load(dir); });
  EXPECT_NE(message.find((dir / "model.pt").string() + "' is not the weights"), std::string::npos) << message;
  // The weights of another width.
  o.width = 4;
  CnnClassifier::fit(train.rows, train.labels, AsvClasses::three(), o).save(dir / "narrow", {});
  std::filesystem::copy_file(dir / "narrow" / "model.pt", dir / "model.pt",
                             std::filesystem::copy_options::overwrite_existing);
  message = testing::input_error_of([&] { CnnClassifier::load(dir); });
  EXPECT_NE(message.find("is not the weights of the network model.json describes ('features.0.weight' has another "
                         "shape)"),
            std::string::npos)
      << message;
  // A traits model is not a network, and the reverse.
  const auto traits = dir / "traits";
  std::filesystem::create_directories(traits);
  std::ofstream(traits / "model.json") << R"({"format": "riceasv traits classifier", "version": 1})";
  EXPECT_FALSE(CnnClassifier::is_cnn_model(traits));
  message = testing::input_error_of([&] { CnnClassifier::load(traits); });
  EXPECT_NE(message.find("is not a riceasv cnn classifier"), std::string::npos) << message;
  message = testing::input_error_of([&] { TraitClassifier::load(dir / "narrow"); });
  EXPECT_NE(message.find("is not a riceasv traits classifier"), std::string::npos) << message;
}

TEST(GrainCnn, SelectionKeepsThePassWithTheLowestValidationLoss) {
  const Crops train = draw(10, 8), validation = draw(4, 9);
  CnnOptions o = small_options();
  o.max_epochs = 12;
  CnnLearner learner(AsvClasses::three(), o);
  std::vector<Prediction> predicted;
  const auto s = learner.select(train.rows, train.labels, validation.rows, validation.labels, predicted);
  const auto loss = s["validation_loss"].get<std::vector<double>>();
  ASSERT_EQ(loss.size(), 12u);
  const int chosen = s["epochs"].get<int>();
  EXPECT_EQ(learner.options().epochs, chosen);
  EXPECT_EQ(loss[static_cast<std::size_t>(chosen - 1)], *std::min_element(loss.begin(), loss.end()));
  ASSERT_EQ(predicted.size(), validation.labels.size());
  // The kept predictions are the chosen pass's: their accuracy is the curve's at that pass.
  EXPECT_DOUBLE_EQ(accuracy(predicted, validation.labels),
                   s["validation_accuracy"][static_cast<std::size_t>(chosen - 1)].get<double>());
}

}  // namespace
}  // namespace suite::rice
