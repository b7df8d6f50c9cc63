#include "rice/classify/fitted_model.hpp"

#include <fmt/format.h>

#include <fstream>

#include "core/errors.hpp"

namespace suite::rice {

void create_model_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw InputError(fmt::format("cannot create the model folder '{}': {}; choose a folder you can write", dir.string(),
                                 ec.message()));
}

nlohmann::json classes_json(const AsvClasses& classes) {
  nlohmann::json grades = nlohmann::json::array();
  for (int c = 0; c < classes.count(); ++c) grades.push_back(classes.grades_of(c));
  return {{"scheme", classes.scheme}, {"names", classes.names}, {"grades", grades}};
}

std::string model_format(const std::filesystem::path& dir) {
  std::ifstream in(dir / "model.json");
  if (!in) return "";
  const auto j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() ? j.value("format", "") : "";
}

std::vector<Prediction> most_probable(const cv::Mat& probabilities) {
  std::vector<Prediction> out(static_cast<std::size_t>(probabilities.rows));
  for (int i = 0; i < probabilities.rows; ++i) {
    cv::Point best;
    double top = 0;
    cv::minMaxLoc(probabilities.row(i), nullptr, &top, nullptr, &best);
    out[static_cast<std::size_t>(i)] = {best.x, top};
  }
  return out;
}

}  // namespace suite::rice
