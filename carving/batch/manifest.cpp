#include "carving/batch/manifest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "core/config/suggest.hpp"
#include "core/errors.hpp"
#include "core/io/csv_table.hpp"

namespace suite::carving {
namespace {

const std::vector<std::string> kColumns = {"id", "images", "method", "weight_mg", "profile"};

bool is_image(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".bmp" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff";
}

}  // namespace

std::vector<SeedEntry> read_manifest(const std::filesystem::path& manifest) {
  const io::CsvTable table = io::CsvTable::read(manifest);
  for (const std::string& c : table.columns())
    if (std::find(kColumns.begin(), kColumns.end(), c) == kColumns.end()) {
      const auto near = closest_match(c, kColumns);
      throw InputError(fmt::format("{}: unknown column '{}'{}; the columns are {}", manifest.string(), c,
                                   near ? fmt::format(" (did you mean '{}'?)", *near) : "", join(kColumns)));
    }
  for (const char* required : {"id", "images"})
    if (std::find(table.columns().begin(), table.columns().end(), required) == table.columns().end())
      throw InputError(
          fmt::format("{}: no '{}' column; a manifest needs at least id,images", manifest.string(), required));
  auto has = [&](const std::string& c) {
    return std::find(table.columns().begin(), table.columns().end(), c) != table.columns().end();
  };
  const std::filesystem::path base = manifest.parent_path();
  auto resolve = [&](const std::string& p) {
    const std::filesystem::path path(p);
    return path.is_absolute() || base.empty() ? path : base / path;
  };
  std::vector<SeedEntry> seeds;
  std::set<std::string> ids;
  std::map<std::string, std::string> folders;  // safe folder name -> the id that has it
  for (std::size_t r = 0; r < table.rows(); ++r) {
    SeedEntry s;
    s.id = table.text(r, "id");
    const std::string where = fmt::format("{}: seed '{}' (row {})", manifest.string(), s.id, r + 1);
    if (s.id.empty()) throw InputError(fmt::format("{}: row {} has an empty id", manifest.string(), r + 1));
    if (!ids.insert(s.id).second) throw InputError(fmt::format("{}: the id appears twice; ids must be unique", where));
    const auto [folder, fresh] = folders.emplace(safe_folder_name(s.id), s.id);
    if (!fresh)
      throw InputError(
          fmt::format("{}: ids '{}' and '{}' would share the output folder '{}' (letters other than "
                      "A-Z, a-z, 0-9, '-', '_' and '.' become '_'); rename one",
                      where, folder->second, s.id, folder->first));
    const std::string images = table.text(r, "images");
    std::size_t start = 0;
    while (start <= images.size()) {
      const std::size_t end = std::min(images.find(';', start), images.size());
      std::string part = images.substr(start, end - start);
      part.erase(0, part.find_first_not_of(' '));
      part.erase(part.find_last_not_of(' ') + 1);
      if (!part.empty()) s.images.push_back(resolve(part));
      start = end + 1;
    }
    if (s.images.empty())
      throw InputError(fmt::format("{}: no images; give a folder or files separated by ';'", where));
    if (has("method")) {
      s.method = table.text(r, "method");
      if (!s.method.empty() && s.method != "carving" && s.method != "slicing")
        throw InputError(
            fmt::format("{}: method '{}'; use carving or slicing (or leave it empty for the "
                        "profile's)",
                        where, s.method));
    }
    if (has("weight_mg") && !table.text(r, "weight_mg").empty()) {
      s.weight_mg = table.number(r, "weight_mg");
      if (!(*s.weight_mg > 0))
        throw InputError(fmt::format("{}: weight_mg = {} must be > 0 (or empty when not weighed)", where,
                                     table.text(r, "weight_mg")));
    }
    if (has("profile") && !table.text(r, "profile").empty()) s.profile = resolve(table.text(r, "profile"));
    seeds.push_back(std::move(s));
  }
  return seeds;
}

std::vector<std::filesystem::path> seed_image_files(const SeedEntry& seed) {
  std::vector<std::filesystem::path> files;
  if (seed.images.size() == 1 && std::filesystem::is_directory(seed.images[0])) {
    for (const auto& e : std::filesystem::directory_iterator(seed.images[0]))
      if (e.is_regular_file() && is_image(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    if (files.empty())
      throw InputError(fmt::format("seed '{}': folder '{}' holds no image (.png, .bmp, .jpg, .tif)", seed.id,
                                   seed.images[0].string()));
    return files;
  }
  for (const auto& f : seed.images)
    if (!std::filesystem::is_regular_file(f))
      throw InputError(fmt::format("seed '{}': image '{}' does not exist", seed.id, f.string()));
  return seed.images;
}

std::string safe_folder_name(const std::string& id) {
  std::string out = id;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  if (out.empty() || out == "." || out == "..") out = "_" + out;
  return out;
}

}  // namespace suite::carving
