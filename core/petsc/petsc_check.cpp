#include "core/petsc/petsc_check.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace suite {

void check_petsc(PetscErrorCode rc, const char* call, std::source_location loc) {
  if (rc == 0) return;
  const char* text = nullptr;
  if (PetscErrorMessage(static_cast<int>(rc), &text, nullptr) != 0 || text == nullptr) text = "unknown PETSc error";
  throw LibraryError(
      fmt::format("PETSc call {} failed with code {}: {} at {}", call, static_cast<int>(rc), text, where(loc)));
}

}  // namespace suite
