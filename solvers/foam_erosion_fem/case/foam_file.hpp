#pragma once
// Writing OpenFOAM dictionaries: the FoamFile header and number formatting that round-trips.
#include <filesystem>
#include <string>

namespace suite::foam_erosion {

// "FoamFile { version 2.0; format ascii; class <cls>; location "<loc>"; object <obj>; }" and the
// banner line OpenFOAM's own files carry.
std::string foam_header(const std::string& cls, const std::string& object, const std::string& location = "");
// Shortest decimal text that reads back as the same double ("%.17g" trimmed).
std::string foam_number(double v);
// Writes `text` to case_dir/relative (folders created), through a temporary file and a rename.
void write_case_file(const std::filesystem::path& case_dir, const std::filesystem::path& relative,
                     const std::string& text);

}  // namespace suite::foam_erosion
