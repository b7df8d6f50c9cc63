#pragma once
// The labelled photographs a classifier is trained on (docs/rice.md, "Training"), in either layout:
//   a folder of grade folders   LABELS/grade_2/*.png ... LABELS/grade_7/ (or LABELS/2/ ... LABELS/7/);
//                               every image in a grade folder is of that grade. Files beside the grade
//                               folders are ignored; a folder that names no grade is an InputError.
//   a labels CSV                columns `image` and `grade` (other columns are ignored, so a render's
//                               truth.csv serves); a relative image path is taken from the CSV's
//                               folder; an image listed twice must have the same grade both times.
// A grade folder without images is not fatal: it is reported in `problems` and the others are used.
// Not collective.
#include <filesystem>
#include <string>
#include <vector>

namespace suite::rice {

struct LabelledImage {
  std::filesystem::path path;
  int grade = 0;
};

struct LabelledSet {
  std::string layout;  // "grade folders" or "labels CSV"
  std::vector<LabelledImage> images;
  std::vector<std::string> problems;  // one line each: what was skipped and what to do
};

// InputError naming the path and the layouts when LABELS is neither, or holds a bad grade.
LabelledSet read_labelled_images(const std::filesystem::path& labels);

// The grade a folder's name gives ("grade_4", "Grade-4", "4"), or 0 when it names none.
int grade_of_folder(const std::string& name);

}  // namespace suite::rice
