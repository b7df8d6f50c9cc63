#pragma once
// The command that draws a study folder's charts: Debian's python3 with matplotlib running
// plot/plot_study.py (their paths are fixed at configure time).
#include <filesystem>
#include <string>

namespace suite::studies {

std::string plot_command(const std::filesystem::path& study_dir);

}  // namespace suite::studies
