#include "core/run/executable_path.hpp"

#include <system_error>

namespace suite {

std::filesystem::path executable_dir() {
  std::error_code ec;
  return std::filesystem::read_symlink("/proc/self/exe", ec).parent_path();
}

}  // namespace suite
