#pragma once
// `breach scene.yaml --dakota params.in results.out`: the breach model as a Dakota analysis
// driver (core/dakota/analysis_driver.hpp: variables are scene keys, responses summary keys),
// in-process: the summary is the library call's.
#include <filesystem>
#include <string>
#include <vector>

#include "core/config/config.hpp"

namespace suite::breach {

// `scene_file` empty: the embedded default scene (`embedded_text`). Returns the exit status.
int run_dakota_driver(const std::optional<std::filesystem::path>& scene_file, const std::string& embedded_text,
                      const std::vector<std::string>& overrides, const std::filesystem::path& parameters,
                      const std::filesystem::path& results);

}  // namespace suite::breach
