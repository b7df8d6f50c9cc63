#include "studies/plot/plot_command.hpp"

#include "core/run/chart_command.hpp"

namespace suite::studies {

std::string plot_command(const std::filesystem::path& dir) {
  return chart_command(SUITE_STUDIES_PYTHON, SUITE_STUDIES_PLOT_SCRIPT, dir);
}

}  // namespace suite::studies
