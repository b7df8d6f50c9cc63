#include "solvers/breach/io/plot_command.hpp"

#include "core/run/chart_command.hpp"

namespace suite::breach {

std::string plot_command(const std::filesystem::path& out) {
  return chart_command(SUITE_BREACH_PYTHON, SUITE_BREACH_PLOT_SCRIPT, out);
}

}  // namespace suite::breach
