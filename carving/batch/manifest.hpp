#pragma once
// A seed batch's manifest (docs/methods/carving.md, "Batch"): a CSV table, one row per seed.
//
//   id,images,method,weight_mg,profile
//   W-001,seeds/W-001,carving,38.2,wheat_turntable.yaml
//   W-002,seeds/W-002/top.png;seeds/W-002/side.png,slicing,,wheat_two_view.yaml
//
// id and images are required; images is a folder (its .png/.bmp/.jpg/.jpeg/.tif/.tiff files in
// name order) or files separated by ';'. method (carving or slicing) and profile (a calibration
// profile) fall back to the batch's defaults; weight_mg may be empty. Relative paths are relative
// to the manifest's folder. Unknown columns and repeated ids are errors naming the line. Whether
// the images exist is checked per seed, when it is measured: a missing file fails that seed only.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace suite::carving {

struct SeedEntry {
  std::string id;
  std::vector<std::filesystem::path> images;  // a folder (one entry) or files
  std::string method;                         // "" = the batch's default
  std::optional<double> weight_mg;
  std::filesystem::path profile;  // "" = the batch's default
};

std::vector<SeedEntry> read_manifest(const std::filesystem::path& manifest);

// The image files of a seed: a folder's images in name order, or the files as given. Throws
// InputError naming the folder or file when it is missing or a folder holds no image.
std::vector<std::filesystem::path> seed_image_files(const SeedEntry& seed);

// A seed id that is safe as a folder name ("W-001" stays, "a/b c" becomes "a_b_c").
std::string safe_folder_name(const std::string& id);

}  // namespace suite::carving
