#pragma once
// `breach scene.yaml --dakota params.in results.out`: the breach model as a Dakota analysis
// driver (spec/studies.md). Each variable of the parameters file is named by a scene key and
// overrides it (its value in the key's SI unit, e.g. soil.erodibility in m^3/(N s)); each
// response is named by a key of summary.json and written, labelled, to the results file. Values
// that make the scene invalid (a negative kd) or a response with no value write "FAIL", which
// Dakota's failure capture understands; a broken parameters file is an InputError.
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
