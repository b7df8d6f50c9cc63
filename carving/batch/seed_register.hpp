#pragma once
// The seeds an output folder holds results for (docs/carving.md, "Batches"): seeds.txt lists their
// ids in the order they were first given (the results table's order), seeds.json their images.
// Every batch or single measurement into a folder adds its seeds to the register, so a second
// manifest into the same folder adds rows instead of replacing the table. Refused, with the
// reason, before anything is measured: an id the folder already holds with other images (it
// would be skipped or overwritten as if it were the same seed), and two ids that would share one
// seed folder (safe_folder_name).
#include <filesystem>
#include <string>
#include <vector>

#include "carving/batch/manifest.hpp"

namespace suite::carving {

// Adds `seeds` to the register of `out` (created with the folder) and returns every id the
// register holds, in order. Not for concurrent writers other than array tasks of one manifest
// (which add the same seeds).
std::vector<std::string> register_seeds(const std::filesystem::path& out, const std::vector<SeedEntry>& seeds);

// The ids of the register of `out`, in order (from seeds.txt); InputError when the folder has none.
std::vector<std::string> registered_ids(const std::filesystem::path& out);

}  // namespace suite::carving
