#pragma once
// Always-on check of PETSc return codes: a non-zero code becomes a LibraryError that names
// the call, the source location and PETSc's own text for the code.
#include <petscsys.h>

#include <source_location>

namespace suite {

void check_petsc(PetscErrorCode rc, const char* call, std::source_location loc = std::source_location::current());

}  // namespace suite

#define SUITE_PETSC_CHECK(call) ::suite::check_petsc((call), #call)
