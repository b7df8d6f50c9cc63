#include "rice/render/render_set.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "rice/measure/image_files.hpp"
#include "rice/render/grade_scale.hpp"

namespace suite::rice {
namespace {

std::string number(double x) {
  return std::isfinite(x) ? fmt::format("{:.6g}", x) : "";
}

// A grain of `grade`: like grade - 1 with probability blend / 2, like grade + 1 with blend / 2 (the
// ends of the scale have one neighbour, drawn with blend / 2).
int blended_grade(int grade, double blend, std::mt19937_64& rng) {
  const double u = std::uniform_real_distribution<double>(0, 1)(rng);
  if (u < blend / 2) return grade > kLowestGrade ? grade - 1 : grade;
  if (u < blend) return grade < kHighestGrade ? grade + 1 : grade;
  return grade;
}

}  // namespace

double blend_ceiling(const std::vector<int>& grades, double blend, const std::vector<int>& classes_of_grade) {
  auto class_of = [&](int g) { return classes_of_grade.at(static_cast<std::size_t>(g - kLowestGrade)); };
  double kept = 0;
  for (int g : grades) {
    double same = 1 - blend;
    same += (g > kLowestGrade ? (class_of(g - 1) == class_of(g)) : 1) * blend / 2;
    same += (g < kHighestGrade ? (class_of(g + 1) == class_of(g)) : 1) * blend / 2;
    kept += same;
  }
  return grades.empty() ? 1.0 : kept / static_cast<double>(grades.size());
}

std::uint64_t image_seed(std::uint64_t seed, int grade, int k) {
  std::seed_seq sequence{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                         static_cast<std::uint32_t>(grade), static_cast<std::uint32_t>(k)};
  std::uint64_t words[2];
  std::uint32_t parts[4];
  sequence.generate(parts, parts + 4);
  words[0] = (static_cast<std::uint64_t>(parts[0]) << 32) | parts[1];
  words[1] = (static_cast<std::uint64_t>(parts[2]) << 32) | parts[3];
  return words[0] ^ (words[1] * 0x9E3779B97F4A7C15ull);
}

std::vector<int> parse_grades(const std::string& text) {
  std::vector<int> grades;
  std::stringstream items(text);
  std::string item;
  auto bad = [&](const std::string& why) {
    return InputError(fmt::format("--grades '{}': {}; give grades from {} to {} separated by commas, e.g. 2,3,4,5,6,7",
                                  text, why, kLowestGrade, kHighestGrade));
  };
  while (std::getline(items, item, ',')) {
    std::size_t used = 0;
    int grade = 0;
    try {
      grade = std::stoi(item, &used);
    } catch (const std::exception&) {
      throw bad(fmt::format("'{}' is not a whole number", item));
    }
    if (used != item.size()) throw bad(fmt::format("'{}' is not a whole number", item));
    if (grade < kLowestGrade || grade > kHighestGrade) throw bad(fmt::format("{} is not on the scale", grade));
    if (std::find(grades.begin(), grades.end(), grade) != grades.end())
      throw bad(fmt::format("{} is given twice", grade));
    grades.push_back(grade);
  }
  if (grades.empty()) throw bad("no grades");
  return grades;
}

const std::vector<std::string>& truth_columns() {
  static const std::vector<std::string> columns = {"image",
                                                   "grain",
                                                   "grade",
                                                   "x_px",
                                                   "y_px",
                                                   "angle_deg",
                                                   "length_mm",
                                                   "width_mm",
                                                   "kernel_area_mm2",
                                                   "gel_area_mm2",
                                                   "gel_kernel_ratio",
                                                   "collar_completeness",
                                                   "kernel_pieces",
                                                   "kernel_share",
                                                   "touching",
                                                   "cut_by_frame",
                                                   "drawn_grade"};
  return columns;
}

void write_truth(const std::filesystem::path& file, const std::vector<TruthRow>& rows, double mm_per_px) {
  std::string text = fmt::format(
      "# riceasv render ground truth, pixel size {} mm: positions in pixels, angle in degrees, lengths in mm, "
      "areas in mm^2; ratio, completeness and share are fractions (ratio empty without a kernel); grade: the "
      "photograph's, drawn_grade: the grade whose appearance the grain was drawn with (render --blend)\n{}\n",
      mm_per_px, fmt::join(truth_columns(), ","));
  for (const auto& r : rows) {
    const GrainSpec& s = r.grain.spec;
    const GrainTruth& t = r.grain.truth;
    text += fmt::format("{},{},{},{:.2f},{:.2f},{:.2f},{:.4f},{:.4f},{},{},{},{},{},{},{},{},{}\n", r.image,
                        r.grain.index, r.grade, s.centre_px.x, s.centre_px.y, s.angle_deg, s.length_mm, s.width_mm,
                        number(t.kernel_area_mm2), number(t.gel_area_mm2), number(t.gel_kernel_ratio),
                        number(t.collar_completeness), t.kernel_pieces, number(t.kernel_share), s.touching ? 1 : 0,
                        r.grain.cut_by_frame ? 1 : 0, s.grade);
  }
  io::write_file_atomic(file, text);
}

RenderedSet render_set(const RenderSetOptions& o, const std::filesystem::path& out) {
  if (o.grades.empty()) throw InputError("render: no grades; give --grades, e.g. 2,3,4,5,6,7");
  if (o.per_grade < 1) throw InputError(fmt::format("--per-grade {}: give at least 1", o.per_grade));
  if (o.per_image < 1) throw InputError(fmt::format("--per-image {}: give at least 1", o.per_image));
  for (int g : o.grades) (void)appearance(g);
  if (!(o.blend >= 0 && o.blend <= 1))
    throw InputError(
        fmt::format("--blend {}: give the share of grains drawn like a neighbouring grade, in [0, 1]", o.blend));
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec)
    throw InputError(fmt::format("cannot create the output folder '{}': {}; choose a folder you can write",
                                 out.string(), ec.message()));
  RenderedSet set;
  for (int grade : o.grades) {
    for (int k = 1, left = o.per_grade; left > 0; ++k) {
      const int n = std::min(left, o.per_image);
      left -= n;
      std::mt19937_64 rng(image_seed(o.seed, grade, k));
      std::vector<int> drawn(static_cast<std::size_t>(n), grade);
      if (o.blend > 0)  // no draw at all without blending: the photographs stay as they were
        for (int& d : drawn) d = blended_grade(grade, o.blend, rng);
      const RenderedDish dish = render_dish(drawn, o.dish, rng);
      const std::string name = fmt::format("asv{}_{:02}.png", grade, k);
      write_png(out / name, dish.image);
      set.images.push_back(out / name);
      for (const auto& g : dish.grains) set.truth.push_back({name, grade, g});
    }
  }
  write_truth(out / "truth.csv", set.truth, o.dish.mm_per_px);
  const nlohmann::json record = {{"program", "riceasv render"},
                                 {"scale", "alkali spreading value, Little et al. (1958), grades 2-7"},
                                 {"grades", o.grades},
                                 {"per_grade", o.per_grade},
                                 {"per_image", o.per_image},
                                 {"seed", o.seed},
                                 {"blend", o.blend},
                                 {"pixel_size_mm", o.dish.mm_per_px},
                                 {"cell_mm", o.dish.cell_mm},
                                 {"dish_level", o.dish.dish_level},
                                 {"lighting_gradient", o.dish.lighting_gradient},
                                 {"blur_mm", o.dish.blur_mm},
                                 {"noise_sigma", o.dish.noise_sigma},
                                 {"touching_pairs_per_image", o.dish.touching_pairs},
                                 {"frame_cut", o.dish.frame_cut},
                                 {"images", set.images.size()},
                                 {"grains", set.truth.size()}};
  io::write_file_atomic(out / "render.json", record.dump(2) + "\n");
  return set;
}

}  // namespace suite::rice
