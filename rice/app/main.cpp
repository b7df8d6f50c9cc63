// riceasv: rice alkali spreading value from photographs (docs/rice.md, issue 32). `render` draws
// synthetic dishes of grains in alkali with their ground truth; `measure` segments each grain and
// its gel and writes the traits a classifier of the grade needs; `train` fits and judges such a
// classifier on labelled photographs; `classify` predicts the class of every grain with it.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/cli/subcommands.hpp"
#include "core/errors.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "core/mpi/environment.hpp"
#include "core/run/guarded_main.hpp"
#include "core/run/shard.hpp"
#include "rice/classify/classify_batch.hpp"
#include "rice/classify/classify_images.hpp"
#include "rice/classify/train_classifier.hpp"
#include "rice/cnn/pretrained_net.hpp"
#include "rice/measure/measure_images.hpp"
#include "rice/render/render_set.hpp"

namespace {

using suite::cli::CommandSpec;
using Option = suite::cli::OptionSpec;

suite::cli::ProgramSpec program_spec() {
  return {"riceasv",
          "riceasv: rice alkali spreading value (grades 2-7, Little et al. 1958) from photographs (docs/rice.md)",
          {
              CommandSpec{"render",
                          "synthetic photographs of milled grains in alkali on a black dish, grades 2-7, with ground "
                          "truth: DIR/asv<grade>_<k>.png, DIR/truth.csv (areas in mm^2, collar completeness, kernel "
                          "pieces per grain) and DIR/render.json",
                          "",
                          0,
                          0,
                          false,
                          {Option::text("out", "DIR", "output folder (created)", true),
                           Option::text("grades", "G,G,...", "grades to draw, from 2 to 7 (default 2,3,4,5,6,7)"),
                           Option::count("per-grade", "N", "grains of each grade (default 6)", 1),
                           Option::count("per-image", "K", "grains per photograph (default 6)", 1),
                           Option::count("seed", "S", "seed of the random draws (default 1)", 0),
                           Option::number("pixel-size", "MM", "size of a pixel on the dish (default 0.02)"),
                           Option::number("noise", "SIGMA", "sensor noise, grey levels (default 4)"),
                           Option::count("touching-pairs", "P",
                                         "per photograph, P cells with two grains touching (grades 2-5; default 0)", 0),
                           Option::flag("frame-cut", "move each photograph's last grain across its right edge"),
                           Option::number("blend", "P",
                                          "share of grains drawn with a neighbouring grade's appearance while "
                                          "their photograph keeps its grade, as scorers disagree at the "
                                          "boundaries (default 0; truth.csv's drawn_grade)")}},
              CommandSpec{"measure",
                          "segment every grain and its gel in each photograph (or folder of them) and write "
                          "DIR/results.csv: one row per grain (kernel area, pieces, solidity, gel area and ratio, "
                          "collar completeness, kernel share), and a failed row for an image that cannot be read",
                          "IMAGES...",
                          1,
                          -1,
                          false,
                          {Option::text("out", "DIR", "output folder (created)", true),
                           Option::number("pixel-size", "MM",
                                          "size of a pixel on the dish, from a ruler or a "
                                          "calibration target (required)"),
                           Option::flag("overlays", "also write DIR/overlays/<image>.png with the outlines")}},
              CommandSpec{"train",
                          "measure labelled photographs (LABELS: a folder of grade folders grade_2/ ... grade_7/ or "
                          "2/ ... 7/, or a CSV with columns image,grade), train a classifier of the ASV class on the "
                          "ok grains' traits, judge it on a seeded train/validation/test split and by k-fold "
                          "cross-validation, and save it: DIR/model.yml + model.json, evaluation.json, "
                          "confusion_test.csv, confusion_cv.csv, confusion.png, samples.csv, measured/",
                          "LABELS",
                          1,
                          1,
                          false,
                          {Option::text("out", "MODEL_DIR", "output folder for the model and its evaluation", true),
                           Option::number("pixel-size", "MM", "size of a pixel on the dish (required)"),
                           Option::text("classes", "three|grades",
                                        "three: low (2-3), medium (4-5), high (6-7), the default; grades: 2 ... 7"),
                           Option::text("model-type", "rtrees|svm|cnn|pretrained",
                                        "random forest on the traits (default), RBF SVM on the traits, a "
                                        "convolutional network on a crop around each grain (libtorch), or your "
                                        "pretrained TorchScript network fine-tuned on the crops"),
                           Option::text("pretrained", "NET",
                                        "with --model-type pretrained: your TorchScript network to fine-tune, NET.pt "
                                        "with NET.json beside it (the ONNX convention) or a folder of net.pt and "
                                        "net.json"),
                           Option::count("trees", "N", "trees of the forest (default 100)", 1),
                           Option::count("epochs", "N",
                                         "cnn, pretrained: most passes over the training crops; the pass with the "
                                         "lowest validation loss is kept (default 80; pretrained 30)",
                                         1),
                           Option::count("batch", "N", "cnn, pretrained: crops per training step (default 16)", 1),
                           Option::number("learning-rate", "R",
                                          "cnn, pretrained: Adam's step size (default 0.003; pretrained 0.0003)"),
                           Option::count("cnn-width", "C", "cnn: channels of the first convolution (default 8)", 1),
                           Option::number("crop-mm", "MM", "cnn: side of the crop around each grain (default 14)"),
                           Option::count("cnn-input", "PX",
                                         "cnn: side of the network's input, the crop resized to it (default 48)", 8),
                           Option::count("threads", "N",
                                         "cnn, pretrained: libtorch threads (default 1; results are "
                                         "reproducible for a given N)",
                                         1),
                           Option::count("folds", "K", "k-fold cross-validation (default 5; 0: none)", 0),
                           Option::number("validation-share", "F", "share of each class for validation (0.125)"),
                           Option::number("test-share", "F", "share of each class held out for the test (0.125)"),
                           Option::count("seed", "S", "seed of the split, the folds and the forest (default 1)", 0)}},
              CommandSpec{"classify",
                          "measure photographs (files or folders) and predict each grain's ASV class with a model "
                          "from `riceasv train` (--model) or a network of your own in ONNX (--onnx, run through "
                          "OpenCV dnn on a crop around each grain): DIR/classes.csv (class and vote share or score "
                          "per grain), DIR/classify.json (counts per class and per image), DIR/results.csv (the "
                          "traits); with --onnx also DIR/scores.csv (every class's score)",
                          "IMAGES...",
                          1,
                          -1,
                          false,
                          {Option::text("out", "DIR", "output folder (created)", true),
                           Option::text("model", "MODEL_DIR", "the folder `riceasv train --out` wrote"),
                           Option::text("onnx", "NET",
                                        "instead of --model: NET.onnx with NET.json beside it (classes, input size, "
                                        "crop_mm, normalisation; docs/rice.md), or a folder holding net.onnx and "
                                        "net.json"),
                           Option::flag("crops",
                                        "with --onnx or a cnn model: also write DIR/crops/<image>_g<grain>.png, "
                                        "each grain as the network sees it before normalisation"),
                           Option::number("pixel-size", "MM", "size of a pixel on the dish (required)"),
                           Option::count("part-size", "N",
                                         "photographs per part (default 50): each part is written to "
                                         "DIR/parts/ when complete, and a rerun into DIR skips finished parts",
                                         1),
                           Option::text("shard", "K/N",
                                        "Slurm array task K of N: the parts with index % N == K; the tables are "
                                        "merged when every part is there (else `riceasv merge DIR`)")}},
              CommandSpec{"merge",
                          "write DIR's tables (classes.csv, results.csv, scores.csv, measure.json, classify.json, "
                          "crops/) from the parts of a `riceasv classify --shard` batch once every part is done",
                          "DIR",
                          1,
                          1,
                          false,
                          {}},
          }};
}

int render(const suite::cli::CommandArguments& c, suite::Logger& log) {
  suite::rice::RenderSetOptions o;
  if (c.has("grades")) o.grades = suite::rice::parse_grades(c.text_or("grades", ""));
  o.per_grade = static_cast<int>(c.count_or("per-grade", o.per_grade));
  o.per_image = static_cast<int>(c.count_or("per-image", o.per_image));
  o.seed = static_cast<std::uint64_t>(c.count_or("seed", 1));
  o.dish.mm_per_px = c.number("pixel-size").value_or(o.dish.mm_per_px);
  o.dish.noise_sigma = c.number("noise").value_or(o.dish.noise_sigma);
  o.dish.touching_pairs = static_cast<int>(c.count_or("touching-pairs", 0));
  o.dish.frame_cut = c.has("frame-cut");
  o.blend = c.number("blend").value_or(0.0);
  const std::filesystem::path out = c.text_or("out", "");
  const auto set = suite::rice::render_set(o, out);
  log.info("{} photographs, {} grains (grades {}), truth in {}", set.images.size(), set.truth.size(),
           fmt::join(o.grades, ","), (out / "truth.csv").string());
  return 0;
}

// The measurement options from --pixel-size, which every command that measures requires.
suite::rice::MeasureOptions measure_options(const suite::cli::CommandArguments& c) {
  const auto pixel = c.number("pixel-size");
  if (!pixel)
    throw suite::InputError(
        fmt::format("riceasv {}: --pixel-size MM is required (the size of one pixel on the dish in mm, e.g. 0.02; "
                    "photograph a ruler at the same height to find it)",
                    c.command));
  suite::rice::MeasureOptions o;
  o.mm_per_px = *pixel;
  if (!(o.mm_per_px > 0) || o.mm_per_px > 1)
    throw suite::InputError(fmt::format("--pixel-size {}: give the size of one pixel in mm, in (0, 1]", o.mm_per_px));
  return o;
}

int measure(const suite::cli::CommandArguments& c, suite::Logger& log) {
  const suite::rice::MeasureOptions o = measure_options(c);
  std::vector<std::filesystem::path> targets(c.targets.begin(), c.targets.end());
  const std::filesystem::path out = c.text_or("out", "");
  const auto rows = suite::rice::measure_images(targets, o, out, c.has("overlays"), log);
  int grains = 0, flagged = 0, failed = 0;
  const suite::rice::ResultRow* first_failed = nullptr;
  for (const auto& r : rows) {
    if (r.status == "failed") {
      ++failed;
      if (!first_failed) first_failed = &r;
    } else {
      ++grains;
      flagged += r.status == "flagged";
    }
  }
  log.info("{} grains ({} flagged) from {} images; table {}", grains, flagged, rows.empty() ? 0 : rows.size(),
           (out / "results.csv").string());
  if (failed > 0)
    throw suite::InputError(fmt::format("{} image(s) could not be measured, the others were (table {}); first: {}",
                                        failed, (out / "results.csv").string(), first_failed->message));
  return 0;
}

int train(const suite::cli::CommandArguments& c, suite::Logger& log) {
  const suite::rice::MeasureOptions m = measure_options(c);
  suite::rice::TrainOptions o;
  o.classes = suite::rice::AsvClasses::parse(c.text_or("classes", "three"));
  o.model.kind = suite::rice::parse_model_kind(c.text_or("model-type", "rtrees"));
  o.model.trees = static_cast<int>(c.count_or("trees", o.model.trees));
  o.folds = static_cast<int>(c.count_or("folds", o.folds));
  o.validation_share = c.number("validation-share").value_or(o.validation_share);
  o.test_share = c.number("test-share").value_or(o.test_share);
  o.seed = static_cast<std::uint64_t>(c.count_or("seed", 1));
  using suite::rice::ModelKind;
  const bool pretrained = o.model.kind == ModelKind::pretrained;
  if (pretrained) o.cnn = suite::rice::fine_tuning_options();
  if (pretrained != c.has("pretrained"))
    throw suite::InputError("riceasv train: --pretrained NET goes with --model-type pretrained (and it needs one)");
  o.pretrained = c.text_or("pretrained", "");
  o.cnn.max_epochs = static_cast<int>(c.count_or("epochs", o.cnn.max_epochs));
  o.cnn.width = static_cast<int>(c.count_or("cnn-width", o.cnn.width));
  o.cnn.batch = static_cast<int>(c.count_or("batch", o.cnn.batch));
  o.cnn.learning_rate = c.number("learning-rate").value_or(o.cnn.learning_rate);
  if (!(o.cnn.learning_rate > 0) || o.cnn.learning_rate > 1)
    throw suite::InputError(fmt::format("--learning-rate {}: give a step size in (0, 1]", o.cnn.learning_rate));
  o.cnn.crop_mm = c.number("crop-mm").value_or(o.cnn.crop_mm);
  o.cnn.input_px = static_cast<int>(c.count_or("cnn-input", o.cnn.input_px));
  o.cnn.threads = static_cast<int>(c.count_or("threads", o.cnn.threads));
  if (!(o.cnn.crop_mm > 0) || o.cnn.crop_mm > 100)
    throw suite::InputError(fmt::format("--crop-mm {}: give the crop's side in mm, in (0, 100]", o.cnn.crop_mm));
  for (const char* key : {"epochs", "batch", "learning-rate", "threads"})
    if (c.has(key) && o.model.kind != ModelKind::cnn && !pretrained)
      throw suite::InputError(fmt::format(
          "riceasv train: --{} is an option of the network; add --model-type cnn (or pretrained) or leave it out",
          key));
  for (const char* key : {"cnn-width", "crop-mm", "cnn-input"})
    if (c.has(key) && o.model.kind != ModelKind::cnn)
      throw suite::InputError(
          fmt::format("riceasv train: --{} is an option of the suite's network; add --model-type cnn or leave it out{}",
                      key, pretrained ? " (a pretrained network's crop and input come from its net.json)" : ""));
  const std::filesystem::path out = c.text_or("out", "");
  const auto s = suite::rice::train_classifier(c.targets.at(0), o, m, out, log);
  if (!s.problems.empty())
    throw suite::InputError(
        fmt::format("{} labelled image(s) or folder(s) could not be used, the model was trained "
                    "on the others ({}); first: {}",
                    s.problems.size(), (out / "evaluation.json").string(), s.problems.front()));
  return 0;
}

int classify(const suite::cli::CommandArguments& c, suite::Logger& log) {
  const suite::rice::MeasureOptions m = measure_options(c);
  std::vector<std::filesystem::path> targets(c.targets.begin(), c.targets.end());
  const std::filesystem::path out = c.text_or("out", "");
  if (c.has("model") == c.has("onnx"))
    throw suite::InputError(
        "riceasv classify: give either --model MODEL_DIR (a folder from `riceasv train`) or --onnx NET (a network "
        "of your own in ONNX, with NET.json beside it; docs/rice.md), not both and not neither");
  const bool onnx = c.has("onnx"), crops = c.has("crops");
  const std::filesystem::path model = c.text_or(onnx ? "onnx" : "model", "");
  const suite::rice::PartClassifier part = [&](const std::vector<std::filesystem::path>& images,
                                               const std::filesystem::path& dir) {
    return onnx ? suite::rice::classify_images_onnx(images, model, m, dir, crops, log)
                : suite::rice::classify_images(images, model, m, dir, crops, log);
  };
  suite::rice::BatchOptions batch;
  batch.part_size = static_cast<int>(c.count_or("part-size", batch.part_size));
  if (c.has("shard")) batch.shard = suite::parse_shard(c.text_or("shard", ""));
  const auto s = suite::rice::classify_batch(targets, part, batch, out, log);
  if (s.merged) {
    log.info("{} grains classified ({} flagged) from {} images in {} part(s), {} classified now; table {}",
             s.all.grains, s.all.flagged, s.all.images, s.parts, s.done_now, (out / "classes.csv").string());
  } else {
    log.info("{} of {} part(s) classified now, {} found done; {} part(s) left to other tasks, then `riceasv merge {}`",
             s.done_now, s.parts, s.done_before, s.missing.size(), out.string());
  }
  if (s.now.failed_images > 0)
    throw suite::InputError(fmt::format("{} image(s) could not be classified, the others were (table {}); first: {}",
                                        s.now.failed_images, (s.merged ? out / "classes.csv" : out / "parts").string(),
                                        s.now.first_failure));
  return 0;
}

int merge(const suite::cli::CommandArguments& c, suite::Logger& log) {
  const std::filesystem::path out = c.targets.at(0);
  const auto s = suite::rice::merge_classified(out);
  log.info("{} grains ({} flagged) from {} images merged; table {}", s.grains, s.flagged, s.images,
           (out / "classes.csv").string());
  if (s.failed_images > 0)
    throw suite::InputError(fmt::format("{} image(s) could not be classified, the others were (table {}); first: {}",
                                        s.failed_images, (out / "classes.csv").string(), s.first_failure));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  suite::mpi::Environment env(argc, argv);
  const suite::mpi::Comm world(MPI_COMM_WORLD);
  return suite::guarded_main(world, [&] {
    const auto parsed = suite::cli::parse_command(program_spec(), argc, argv);
    if (!parsed.arguments) {
      if (world.is_root()) std::fputs((parsed.message + "\n").c_str(), parsed.exit_code ? stderr : stdout);
      return parsed.exit_code;
    }
    const auto& c = *parsed.arguments;
    if (world.size() > 1)
      throw suite::InputError(fmt::format("riceasv runs on one process, not {}; run it without mpiexec", world.size()));
    suite::Logger log(world, "riceasv", {suite::parse_log_level(c.log_level), false, nullptr});
    if (c.command == "render") return render(c, log);
    if (c.command == "measure") return measure(c, log);
    if (c.command == "train") return train(c, log);
    if (c.command == "classify") return classify(c, log);
    if (c.command == "merge") return merge(c, log);
    throw std::logic_error("riceasv: command '" + c.command + "' has no handler");
  });
}
