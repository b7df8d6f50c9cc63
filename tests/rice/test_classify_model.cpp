// The saved classifier: a save/load round trip predicts the same, a seed fixes the forest, and a
// model folder that is missing, of another format or another kind of model says which file is wrong
// and how to fix it. And the two layouts of labelled photographs.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "core/mpi/comm.hpp"
#include "rice/classify/labelled_images.hpp"
#include "rice/classify/trait_classifier.hpp"
#include "tests/rice/classify_test_data.hpp"
#include "tests/support/test_dirs.hpp"

namespace suite::rice {
namespace {

// "'path'" as the messages quote it (appended piece by piece: GCC 12 warns falsely on "'" + string).
std::string quoted(const std::filesystem::path& path) {
  std::string q(1, '\'');
  q += path.string();
  q += '\'';
  return q;
}

void write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

TEST(TraitClassifier, SaveAndLoadPredictTheSame) {
  const auto dir = testing::scratch_dir(mpi::Comm(MPI_COMM_SELF));
  const auto train = testdata::samples(10, 1);
  const auto unseen = testdata::samples(8, 2);
  for (ModelKind kind : {ModelKind::rtrees, ModelKind::svm}) {
    ModelOptions o;
    o.kind = kind;
    const auto model = TraitClassifier::fit(train.features, train.labels, AsvClasses::three(), o);
    const auto folder = dir / to_string(kind);
    model.save(folder, {{"note", "test"}});
    const auto loaded = TraitClassifier::load(folder);
    EXPECT_EQ(loaded.classes().names, model.classes().names);
    const auto before = model.predict(unseen.features);
    const auto after = loaded.predict(unseen.features);
    ASSERT_EQ(before.size(), after.size());
    int right = 0;
    for (std::size_t i = 0; i < before.size(); ++i) {
      EXPECT_EQ(before[i].label, after[i].label) << to_string(kind) << " grain " << i;
      if (kind == ModelKind::rtrees)
        EXPECT_EQ(before[i].share, after[i].share) << "grain " << i;
      else
        EXPECT_TRUE(std::isnan(after[i].share));
      right += after[i].label == unseen.labels[i];
    }
    // Not the point here, but a model that classifies the drawn grades at chance would be a broken
    // round trip of the scaling: the grades are apart (see test_classify_evaluation.cpp).
    EXPECT_GT(right, static_cast<int>(0.9 * before.size())) << to_string(kind);
  }
}

TEST(TraitClassifier, TheSeedFixesTheForest) {
  // Features of pure noise with random labels: every tree's vote depends on its bootstrap sample.
  std::mt19937_64 rng(4);
  cv::Mat features(60, static_cast<int>(feature_names().size()), CV_32F);
  cv::randu(features, 0, 1);
  std::vector<int> labels;
  for (int i = 0; i < 60; ++i) labels.push_back(static_cast<int>(rng() % 3));
  auto shares = [&](std::uint64_t seed) {
    ModelOptions o;
    o.seed = seed;
    std::vector<double> s;
    for (const auto& p : TraitClassifier::fit(features, labels, AsvClasses::three(), o).predict(features))
      s.push_back(p.label + p.share);
    return s;
  };
  EXPECT_EQ(shares(1), shares(1));
  EXPECT_NE(shares(1), shares(2));
}

TEST(TraitClassifier, AWrongOrMissingModelNamesTheFileAndTheFix) {
  const auto dir = testing::scratch_dir(mpi::Comm(MPI_COMM_SELF));
  const auto data = testdata::samples(6, 9);
  ModelOptions svm;
  svm.kind = ModelKind::svm;
  TraitClassifier::fit(data.features, data.labels, AsvClasses::three(), {}).save(dir / "forest", {});
  TraitClassifier::fit(data.features, data.labels, AsvClasses::three(), svm).save(dir / "svm", {});
  auto error = [](const std::filesystem::path& d) {
    return testing::input_error_of([&] { TraitClassifier::load(d); });
  };
  const std::string fix = "riceasv train LABELS --out";

  EXPECT_NE(error(dir / "none").find("no such folder"), std::string::npos);
  std::filesystem::create_directories(dir / "empty");
  EXPECT_NE(error(dir / "empty").find(quoted(dir / "empty/model.json") + " is missing"), std::string::npos);
  EXPECT_NE(error(dir / "empty").find(fix), std::string::npos);

  write(dir / "other/model.json", R"({"program": "riceasv render", "grades": [2, 3]})");
  EXPECT_NE(error(dir / "other").find("is not a riceasv traits classifier"), std::string::npos) << error(dir / "other");
  write(dir / "text/model.json", "grade,class\n");
  EXPECT_NE(error(dir / "text").find("is not JSON"), std::string::npos);

  // model.json says rtrees, model.yml holds an SVM: the kind is checked, not assumed.
  std::filesystem::copy(dir / "forest", dir / "swapped");
  std::filesystem::copy_file(dir / "svm/model.yml", dir / "swapped/model.yml",
                             std::filesystem::copy_options::overwrite_existing);
  const std::string swapped = error(dir / "swapped");
  EXPECT_NE(swapped.find(quoted(dir / "swapped/model.yml") + " is not an OpenCV RTrees model"), std::string::npos)
      << swapped;
  EXPECT_NE(swapped.find("opencv_ml_svm"), std::string::npos) << swapped;

  std::filesystem::copy(dir / "forest", dir / "garbage");
  write(dir / "garbage/model.yml", "\x89PNG not a model at all");
  EXPECT_NE(error(dir / "garbage").find("model.yml' is not an OpenCV RTrees model"), std::string::npos)
      << error(dir / "garbage");
  std::filesystem::remove(dir / "garbage/model.yml");
  EXPECT_NE(error(dir / "garbage").find("model.yml' is missing"), std::string::npos);

  // A model trained on other features (an older riceasv) is refused, not misread.
  std::ifstream in(dir / "forest/model.json");
  auto j = nlohmann::json::parse(in);
  j["features"][0] = "gel_kernel_ratio";
  std::filesystem::copy(dir / "forest", dir / "old");
  write(dir / "old/model.json", j.dump());
  EXPECT_NE(error(dir / "old").find("was trained on the features [gel_kernel_ratio, "), std::string::npos);
}

TEST(LabelledImages, GradeFoldersWithAnEmptyOneReported) {
  const auto dir = testing::scratch_dir(mpi::Comm(MPI_COMM_SELF));
  write(dir / "grade_2/a.png", "x");
  write(dir / "grade_2/b.JPG", "x");
  write(dir / "3/c.png", "x");
  std::filesystem::create_directories(dir / "Grade-4");
  write(dir / "notes.txt", "ignored");
  const auto set = read_labelled_images(dir);
  EXPECT_EQ(set.layout, "grade folders");
  ASSERT_EQ(set.images.size(), 3u);
  EXPECT_EQ(set.images[0].grade, 2);
  EXPECT_EQ(set.images[2].grade, 3);
  ASSERT_EQ(set.problems.size(), 1u);
  EXPECT_NE(set.problems[0].find("grade folder " + quoted(dir / "Grade-4") + " holds no images"), std::string::npos);
  EXPECT_EQ(grade_of_folder("grade_7"), 7);
  EXPECT_EQ(grade_of_folder("grade8"), 0);
  EXPECT_EQ(grade_of_folder("misc"), 0);
  write(dir / "misc/x.png", "x");
  EXPECT_NE(testing::input_error_of([&] { read_labelled_images(dir); }).find("sub-folder 'misc' names no grade"),
            std::string::npos);
}

TEST(LabelledImages, ALabelsCsvRelativeToItsFolder) {
  const auto dir = testing::scratch_dir(mpi::Comm(MPI_COMM_SELF));
  write(dir / "labels.csv",
        "# a render's truth.csv has more columns and a row per grain\nimage,grain,grade\n"
        "asv2_01.png,1,2\nasv2_01.png,2,2\n/data/x.png,1,7\n");
  const auto set = read_labelled_images(dir / "labels.csv");
  ASSERT_EQ(set.images.size(), 2u);
  EXPECT_EQ(set.images[0].path, dir / "asv2_01.png");
  EXPECT_EQ(set.images[1].path, std::filesystem::path("/data/x.png"));
  EXPECT_EQ(set.images[1].grade, 7);
  write(dir / "twice.csv", "image,grade\na.png,3\na.png,4\n");
  EXPECT_NE(testing::input_error_of([&] {
              read_labelled_images(dir / "twice.csv");
            }).find("image 'a.png' is labelled both 3 and 4"),
            std::string::npos);
  write(dir / "eight.csv", "image,grade\na.png,8\n");
  EXPECT_NE(testing::input_error_of([&] { read_labelled_images(dir / "eight.csv"); }).find("has grade 8"),
            std::string::npos);
  EXPECT_NE(testing::input_error_of([&] { read_labelled_images(dir / "nothing"); }).find("no such folder or file"),
            std::string::npos);
}

}  // namespace
}  // namespace suite::rice
