#include "core/errors.hpp"

#include <fmt/format.h>
#include <hdf5.h>
#include <mpi.h>

#include <string_view>

namespace suite {

std::string where(const std::source_location& loc) {
  std::string_view file = loc.file_name();
  if (auto pos = file.rfind('/'); pos != std::string_view::npos) file.remove_prefix(pos + 1);
  return fmt::format("{}:{} ({})", file, loc.line(), loc.function_name());
}

void check_mpi(int rc, const char* call, std::source_location loc) {
  if (rc == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  if (MPI_Error_string(rc, text, &len) != MPI_SUCCESS) len = 0;
  throw LibraryError(fmt::format("MPI call {} failed with code {}: {} at {}", call, rc,
                                 std::string_view(text, static_cast<std::size_t>(len)), where(loc)));
}

namespace {
// Collects the innermost (first) message of HDF5's error stack.
herr_t first_h5_error(unsigned n, const H5E_error2_t* err, void* data) {
  auto* out = static_cast<std::string*>(data);
  if (n == 0 && err != nullptr) {
    *out = fmt::format("{} in {}()", err->desc ? err->desc : "", err->func_name ? err->func_name : "?");
  }
  return 0;
}
}  // namespace

long long check_h5(long long id, const char* call, std::source_location loc) {
  if (id >= 0) return id;
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, first_h5_error, &detail);
  H5Eclear2(H5E_DEFAULT);
  throw LibraryError(
      fmt::format("HDF5 call {} failed: {} at {}", call, detail.empty() ? "no HDF5 error stack" : detail, where(loc)));
}

}  // namespace suite
