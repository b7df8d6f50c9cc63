#include "rice/classify/classify_batch.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "rice/measure/image_files.hpp"

namespace suite::rice {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRegister = "batch.json";

fs::path part_dir(const fs::path& out, int part) {
  return out / "parts" / fmt::format("{:04}", part);
}

bool part_complete(const fs::path& out, int part) {
  std::error_code ec;
  return fs::is_regular_file(part_dir(out, part) / "classify.json", ec);
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  const auto j = nlohmann::json::parse(in, nullptr, false);
  if (!in || j.is_discarded() || !j.is_object())
    throw InputError(
        fmt::format("'{}' is missing or not JSON; classify that part again (remove its folder and run "
                    "the same riceasv classify command)",
                    file.string()));
  return j;
}

// The batch's photographs and part size, as DIR/batch.json records them.
struct Register {
  std::vector<std::string> images;
  int part_size = 0;
  int parts() const { return static_cast<int>((images.size() + static_cast<std::size_t>(part_size) - 1) / part_size); }
};

Register read_register(const fs::path& out) {
  const fs::path file = out / kRegister;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError(
        fmt::format("'{}' holds no batch ({} is missing); give the folder `riceasv classify --out` "
                    "wrote",
                    out.string(), file.string()));
  const auto j = read_json(file);
  Register r;
  try {
    r.images = j.at("images").get<std::vector<std::string>>();
    r.part_size = j.at("part_size").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("'{}' lacks the batch's images or part size ({}); classify into a new folder",
                                 file.string(), e.what()));
  }
  if (r.part_size < 1 || r.images.empty())
    throw InputError(fmt::format("'{}': no images or a part size below 1; classify into a new folder", file.string()));
  return r;
}

// A table of every part's rows: the first part's '#' lines and header, then each part's rows.
void concatenate_table(const Register& r, const fs::path& out, const std::string& name) {
  std::string text;
  for (int p = 0; p < r.parts(); ++p) {
    std::ifstream in(part_dir(out, p) / name);
    if (!in) {
      if (p == 0) return;  // a table the model does not write (scores.csv of a traits model)
      throw InputError(fmt::format("part {} of '{}' lacks {}; classify that part again", p, out.string(), name));
    }
    std::string line;
    bool header_seen = false;
    while (std::getline(in, line)) {
      const bool preamble = !header_seen && (line.empty() || line[0] == '#');
      if (!preamble && !header_seen) {
        header_seen = true;
        if (p > 0) continue;  // the header, once
      } else if (preamble && p > 0) {
        continue;
      }
      text += line + "\n";
    }
  }
  io::write_file_atomic(out / name, text);
}

}  // namespace

BatchSummary classify_batch(const std::vector<fs::path>& targets, const PartClassifier& classify_part,
                            const BatchOptions& options, const fs::path& out, Logger& log) {
  if (options.part_size < 1) throw InputError(fmt::format("--part-size {}: give at least 1", options.part_size));
  std::vector<std::string> images;
  for (const auto& image : expand_image_arguments(targets)) images.push_back(image.string());
  if (images.empty()) {
    std::vector<std::string> given;
    for (const auto& t : targets) given.push_back(t.string());
    throw InputError(
        fmt::format("no photographs in {} (folders are searched for .png, .jpg, .jpeg, .tif, .tiff, "
                    ".bmp); give photographs or folders holding them",
                    fmt::join(given, ", ")));
  }

  // The register: a rerun must be the same batch, cut the same way.
  std::error_code ec;
  fs::create_directories(out / "parts", ec);
  if (ec)
    throw InputError(fmt::format("cannot create the output folder '{}': {}; choose a folder you can write",
                                 out.string(), ec.message()));
  if (fs::exists(out / kRegister, ec)) {
    const Register before = read_register(out);
    if (before.images != images || before.part_size != options.part_size)
      throw InputError(fmt::format(
          "'{}' holds a batch of {} photograph(s) in parts of {} ({}); this run gives {} in parts of {}: give another "
          "--out, or the same photographs and --part-size to resume it",
          out.string(), before.images.size(), before.part_size, (out / kRegister).string(), images.size(),
          options.part_size));
  } else {
    io::write_file_atomic(
        out / kRegister,
        nlohmann::json({{"program", "riceasv classify"}, {"part_size", options.part_size}, {"images", images}})
                .dump(1) +
            "\n");
  }
  Register batch{images, options.part_size};

  BatchSummary s;
  s.parts = batch.parts();
  for (int p = 0; p < s.parts; ++p) {
    if (options.shard.count > 0 && p % options.shard.count != options.shard.index) {
      if (!part_complete(out, p)) s.missing.push_back(p);
      continue;
    }
    if (part_complete(out, p)) {
      ++s.done_before;
      continue;
    }
    const std::size_t first = static_cast<std::size_t>(p) * static_cast<std::size_t>(options.part_size);
    const std::size_t last = std::min(images.size(), first + static_cast<std::size_t>(options.part_size));
    const std::vector<fs::path> slice(images.begin() + static_cast<std::ptrdiff_t>(first),
                                      images.begin() + static_cast<std::ptrdiff_t>(last));
    fs::path partial = part_dir(out, p);
    partial += ".partial";
    fs::remove_all(partial, ec);  // what a killed run left
    const ClassifySummary c = classify_part(slice, partial);
    fs::remove_all(part_dir(out, p), ec);  // an incomplete folder (no classify.json) is replaced
    fs::rename(partial, part_dir(out, p));
    ++s.done_now;
    s.now.images += c.images;
    s.now.failed_images += c.failed_images;
    s.now.grains += c.grains;
    s.now.flagged += c.flagged;
    if (s.now.first_failure.empty()) s.now.first_failure = c.first_failure;
    log.info("part {} of {} (photographs {}-{}): {} grains ({} flagged), {} image(s) failed", p + 1, s.parts, first + 1,
             last, c.grains, c.flagged, c.failed_images);
  }
  if (s.missing.empty()) {
    s.all = merge_classified(out);
    s.merged = true;
  }
  return s;
}

ClassifySummary merge_classified(const fs::path& out) {
  const Register r = read_register(out);
  std::vector<int> missing;
  for (int p = 0; p < r.parts(); ++p)
    if (!part_complete(out, p)) missing.push_back(p);
  if (!missing.empty())
    throw InputError(fmt::format(
        "'{}': {} of {} part(s) are not classified yet (parts {}); run the array tasks that hold them, or the "
        "same riceasv classify command without --shard, then merge",
        out.string(), missing.size(), r.parts(), fmt::join(missing, ", ")));

  for (const char* table : {"classes.csv", "results.csv", "scores.csv"}) concatenate_table(r, out, table);

  nlohmann::json classify, measure;
  double predict_seconds = 0;
  long predicted = 0;
  std::error_code ec;
  for (int p = 0; p < r.parts(); ++p) {
    const fs::path dir = part_dir(out, p);
    const auto c = read_json(dir / "classify.json");
    const auto m = read_json(dir / "measure.json");
    const long grains = c.value("grains_ok", 0L) + c.value("grains_flagged", 0L);
    predict_seconds += c.value("predict_seconds_per_grain", 0.0) * static_cast<double>(grains);
    predicted += grains;
    if (p == 0) {
      classify = c;
      measure = m;
    } else {
      for (const char* key : {"grains_ok", "grains_flagged", "images_failed"})
        classify[key] = classify.value(key, 0L) + c.value(key, 0L);
      for (const auto& [name, count] : c.at("counts").items())
        classify["counts"][name] = classify["counts"].value(name, 0L) + count.get<long>();
      for (const auto& image : c.at("images")) classify["images"].push_back(image);
      for (const auto& image : m.at("images")) measure["images"].push_back(image);
    }
    if (fs::is_directory(dir / "crops", ec)) {
      fs::create_directories(out / "crops");
      for (const auto& crop : fs::directory_iterator(dir / "crops"))
        fs::copy_file(crop.path(), out / "crops" / crop.path().filename(), fs::copy_options::overwrite_existing);
    }
  }
  classify["predict_seconds_per_grain"] = predicted > 0 ? predict_seconds / static_cast<double>(predicted) : 0.0;
  classify["parts"] = r.parts();
  classify["part_size"] = r.part_size;
  io::write_file_atomic(out / "classify.json", classify.dump(2) + "\n");
  io::write_file_atomic(out / "measure.json", measure.dump(2) + "\n");

  ClassifySummary s;
  s.images = static_cast<int>(classify.at("images").size());
  s.failed_images = classify.value("images_failed", 0);
  s.grains = classify.value("grains_ok", 0);
  s.flagged = classify.value("grains_flagged", 0);
  for (const auto& image : classify.at("images"))
    if (image.contains("failed")) {
      s.first_failure = image.at("failed").get<std::string>();
      break;
    }
  return s;
}

}  // namespace suite::rice
