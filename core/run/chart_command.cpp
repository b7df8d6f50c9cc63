#include "core/run/chart_command.hpp"

#include <fmt/format.h>

namespace suite {

std::string shell_quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string chart_command(const std::string& python, const std::string& script, const std::filesystem::path& dir) {
  return fmt::format("{} {} {} > {} 2>&1", shell_quote(python), shell_quote(script), shell_quote(dir.string()),
                     shell_quote((dir / "plot.log").string()));
}

}  // namespace suite
