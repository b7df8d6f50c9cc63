#pragma once
// Where the running executable lives, for what is installed beside it (a study's `{bindir}`,
// seedcarve's image-format plugin).
#include <filesystem>

namespace suite {

// The folder of the running executable (from /proc/self/exe); empty if it cannot be read.
std::filesystem::path executable_dir();

}  // namespace suite
