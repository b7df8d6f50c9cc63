#pragma once
// The command that draws hydrographs.png from a breach output folder: Debian's python3 with
// matplotlib running plot/plot_breach.py (their paths are fixed at configure time).
#include <filesystem>
#include <string>

namespace suite::breach {

std::string plot_command(const std::filesystem::path& out);

}  // namespace suite::breach
