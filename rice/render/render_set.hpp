#pragma once
// A set of synthetic dish photographs with their ground truth, for testing the measurement and
// training classifiers (docs/rice.md): for each grade, `per_grade` grains drawn `per_image` to a
// photograph, written as OUT/asv<grade>_<k>.png, OUT/truth.csv (one row per grain) and
// OUT/render.json (the options and the seed). Each photograph's random draws come from
// (seed, grade, k) alone, so a photograph is the same whatever other grades the set holds.
// `blend` P draws a share P of the grains with a neighbouring grade's appearance while their
// photograph keeps its grade (truth.csv: `grade` the photograph's, `drawn_grade` the appearance):
// grade g's grain looks like g - 1 with probability P/2 and like g + 1 with probability P/2 (grade 2
// only up, 7 only down, each still P/2). Scorers disagree at the boundaries between neighbouring
// grades, and a grade is given to a dish; a classifier of these photographs cannot beat the share of
// grains whose appearance is in their label's class (blend_ceiling()).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rice/render/dish_renderer.hpp"

namespace suite::rice {

struct RenderSetOptions {
  std::vector<int> grades{2, 3, 4, 5, 6, 7};
  int per_grade = 6;  // grains of each grade
  int per_image = 6;  // grains per photograph (a dish)
  std::uint64_t seed = 1;
  double blend = 0;  // share of grains drawn with a neighbouring grade's appearance, in [0, 1]
  DishOptions dish;
};

struct TruthRow {
  std::string image;  // file name, e.g. asv5_01.png
  int grade = 0;      // the photograph's grade (the label); grain.spec.grade is the appearance drawn
  RenderedGrain grain;
};

struct RenderedSet {
  std::vector<std::filesystem::path> images;
  std::vector<TruthRow> truth;
};

// Renders the set into `out` (created). InputError for options out of range, naming the option,
// or a folder that cannot be written.
RenderedSet render_set(const RenderSetOptions& options, const std::filesystem::path& out);

// The image's random draws: a function of (seed, grade, k) only.
std::uint64_t image_seed(std::uint64_t seed, int grade, int k);

// truth.csv: the columns of truth_columns(), a '#' line with the units first.
const std::vector<std::string>& truth_columns();
void write_truth(const std::filesystem::path& file, const std::vector<TruthRow>& rows, double mm_per_px);

// The expected share of grains of `grades` (equal numbers of each) whose drawn appearance lies in the
// class of their label with `blend` (rows of `classes_of_grade`: the class of each grade 2..7): the
// best accuracy any classifier of the appearance can expect.
double blend_ceiling(const std::vector<int>& grades, double blend, const std::vector<int>& classes_of_grade);

// "2,3,4" -> {2, 3, 4}; InputError naming `text` unless every item is a grade 2..7 given once.
std::vector<int> parse_grades(const std::string& text);

}  // namespace suite::rice
