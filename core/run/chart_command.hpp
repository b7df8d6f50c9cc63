#pragma once
// The shell command that draws an output folder's charts with a Python script (matplotlib, run
// by Debian's python3): `<python> <script> <dir> > <dir>/plot.log 2>&1`, every part quoted.
// Solvers run it after their results are written; a failure costs the charts, never the results.
#include <filesystem>
#include <string>

namespace suite {

std::string shell_quote(const std::string& text);
std::string chart_command(const std::string& python, const std::string& script, const std::filesystem::path& dir);

}  // namespace suite
