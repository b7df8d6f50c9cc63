#include "solvers/breach/io/plot_command.hpp"

#include <fmt/format.h>

namespace suite::breach {

namespace {
// Single-quoted for the shell.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

std::string plot_command(const std::filesystem::path& out) {
  return fmt::format("{} {} {} > {} 2>&1", quoted(SUITE_BREACH_PYTHON), quoted(SUITE_BREACH_PLOT_SCRIPT),
                     quoted(out.string()), quoted((out / "plot.log").string()));
}

}  // namespace suite::breach
