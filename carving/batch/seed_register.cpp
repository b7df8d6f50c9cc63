#include "carving/batch/seed_register.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"

namespace suite::carving {
namespace {

// An image path as the register keeps it: absolute and normalised, so that the same files
// named from another working folder compare equal.
std::string key(const std::filesystem::path& p) {
  return std::filesystem::absolute(p).lexically_normal().string();
}

std::vector<std::string> keys(const std::vector<std::filesystem::path>& images) {
  std::vector<std::string> out;
  for (const auto& p : images) out.push_back(key(p));
  return out;
}

}  // namespace

std::vector<std::string> registered_ids(const std::filesystem::path& out) {
  std::ifstream in(out / "seeds.txt");
  if (!in)
    throw InputError(
        fmt::format("'{}' is not a seed results folder (no seeds.txt); measure seeds into it first", out.string()));
  std::vector<std::string> ids;
  for (std::string id; std::getline(in, id);) ids.push_back(id);
  return ids;
}

std::vector<std::string> register_seeds(const std::filesystem::path& out, const std::vector<SeedEntry>& seeds) {
  std::filesystem::create_directories(out);
  std::vector<std::string> ids;
  if (std::filesystem::exists(out / "seeds.txt")) ids = registered_ids(out);
  nlohmann::json images = nlohmann::json::object();
  if (std::ifstream in(out / "seeds.json"); in) {
    std::stringstream text;
    text << in.rdbuf();
    try {
      images = nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fmt::format("{}: not readable ({}); restore it or measure into a new folder",
                                   (out / "seeds.json").string(), e.what()));
    }
  }
  std::map<std::string, std::string> folders;  // safe folder name -> id
  for (const auto& id : ids) folders.emplace(safe_folder_name(id), id);
  for (const auto& seed : seeds) {
    const auto given = keys(seed.images);
    if (images.contains(seed.id)) {
      const auto held = images[seed.id].get<std::vector<std::string>>();
      if (held != given)
        throw InputError(fmt::format(
            "seed '{}': '{}' already holds it, measured from {}; now given {}. Use another --out, or another id "
            "for a different seed",
            seed.id, out.string(), fmt::join(held, ";"), fmt::join(given, ";")));
      continue;
    }
    const auto [folder, fresh] = folders.emplace(safe_folder_name(seed.id), seed.id);
    if (!fresh && folder->second != seed.id)
      throw InputError(
          fmt::format("seed '{}': '{}' already holds seed '{}', whose folder '{}' it would share; "
                      "rename one",
                      seed.id, out.string(), folder->second, folder->first));
    if (fresh) ids.push_back(seed.id);
    images[seed.id] = given;
  }
  std::string text;
  for (const auto& id : ids) text += id + "\n";
  io::write_file_atomic(out / "seeds.txt", text);
  io::write_file_atomic(out / "seeds.json", images.dump(1) + "\n");
  return ids;
}

}  // namespace suite::carving
