#include "solvers/foam_erosion_fem/case/foam_file.hpp"

#include <fmt/format.h>

#include <charconv>

#include "core/io/atomic_file.hpp"

namespace suite::foam_erosion {

std::string foam_header(const std::string& cls, const std::string& object, const std::string& location) {
  std::string loc = location.empty() ? "" : fmt::format("    location    \"{}\";\n", location);
  return fmt::format(
      "/*--- written by foam-erosion (solvers/foam_erosion_fem), OpenFOAM v1912 format ---*/\n"
      "FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       {};\n{}    object      {};\n}}\n\n",
      cls, loc, object);
}

std::string foam_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

void write_case_file(const std::filesystem::path& case_dir, const std::filesystem::path& relative,
                     const std::string& text) {
  const auto path = case_dir / relative;
  std::filesystem::create_directories(path.parent_path());
  io::write_file_atomic(path, text);
}

}  // namespace suite::foam_erosion
