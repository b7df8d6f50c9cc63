#include "rice/classify/labelled_images.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "core/errors.hpp"
#include "core/io/csv_table.hpp"
#include "rice/measure/image_files.hpp"
#include "rice/render/grade_scale.hpp"

namespace suite::rice {
namespace {

constexpr const char* kLayouts =
    "give a folder of grade folders (grade_2/ ... grade_7/, or 2/ ... 7/, each holding that grade's photographs) "
    "or a CSV with columns image,grade";

LabelledSet from_folders(const std::filesystem::path& root) {
  LabelledSet set{"grade folders", {}, {}};
  std::vector<std::pair<int, std::filesystem::path>> folders;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(root, ec)) {
    if (!entry.is_directory()) continue;
    const std::string name = entry.path().filename().string();
    const int grade = grade_of_folder(name);
    if (grade == 0)
      throw InputError(
          fmt::format("labels folder '{}': sub-folder '{}' names no grade; {}", root.string(), name, kLayouts));
    folders.emplace_back(grade, entry.path());
  }
  if (folders.empty())
    throw InputError(fmt::format("labels folder '{}' holds no grade folders; {}", root.string(), kLayouts));
  std::sort(folders.begin(), folders.end());
  for (const auto& [grade, folder] : folders) {
    std::vector<std::filesystem::path> images;
    try {
      images = expand_image_arguments({folder});
    } catch (const InputError&) {
      set.problems.push_back(
          fmt::format("grade folder '{}' holds no images (.png, .jpg, .tif, .bmp); put the "
                      "grade-{} photographs there or remove the folder",
                      folder.string(), grade));
      continue;
    }
    for (auto& image : images) set.images.push_back({image, grade});
  }
  return set;
}

LabelledSet from_csv(const std::filesystem::path& file) {
  const auto table = io::CsvTable::read(file);
  LabelledSet set{"labels CSV", {}, {}};
  std::map<std::string, int> seen;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const std::string& name = table.text(r, "image");
    const double value = table.number(r, "grade");
    const int grade = static_cast<int>(std::lround(value));
    if (value != grade || grade < kLowestGrade || grade > kHighestGrade)
      throw InputError(fmt::format("labels '{}': image '{}' has grade {}; grades are whole numbers from {} to {}",
                                   file.string(), name, table.text(r, "grade"), kLowestGrade, kHighestGrade));
    const auto [it, fresh] = seen.emplace(name, grade);
    if (!fresh) {
      if (it->second != grade)
        throw InputError(fmt::format("labels '{}': image '{}' is labelled both {} and {}; give each image one grade",
                                     file.string(), name, it->second, grade));
      continue;
    }
    const std::filesystem::path given(name);
    const auto path = given.is_absolute() ? given : file.parent_path() / given;
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      throw InputError(fmt::format("labels '{}': image '{}' is a folder; list the image files in it, one per row",
                                   file.string(), name));
    set.images.push_back({path, grade});
  }
  if (set.images.empty()) throw InputError(fmt::format("labels '{}' lists no images; {}", file.string(), kLayouts));
  return set;
}

}  // namespace

int grade_of_folder(const std::string& name) {
  std::string digits = name;
  std::transform(digits.begin(), digits.end(), digits.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* prefix : {"grade_", "grade-", "grade"})
    if (digits.rfind(prefix, 0) == 0) {
      digits = digits.substr(std::string(prefix).size());
      break;
    }
  if (digits.size() != 1 || !std::isdigit(static_cast<unsigned char>(digits[0]))) return 0;
  const int grade = digits[0] - '0';
  return grade >= kLowestGrade && grade <= kHighestGrade ? grade : 0;
}

LabelledSet read_labelled_images(const std::filesystem::path& labels) {
  std::error_code ec;
  if (std::filesystem::is_directory(labels, ec)) return from_folders(labels);
  if (std::filesystem::is_regular_file(labels, ec)) return from_csv(labels);
  throw InputError(fmt::format("labels '{}': no such folder or file; {}", labels.string(), kLayouts));
}

}  // namespace suite::rice
