#pragma once
// PetscInitialize/PetscFinalize on an explicit communicator (PETSC_COMM_WORLD is set to it
// first), after MPI is up. PETSc errors are returned as codes (no traceback printed), so they
// reach check_petsc. `options` is an options-database string such as
// "-drag_ksp_type cg -drag_ksp_rtol 1e-10", usually a scene's petsc_options key; the
// PETSC_OPTIONS environment variable is read as well. COLLECTIVE on `comm`.
//
// PETSc ignores an option no object asks for, so a misspelt one would change nothing without a
// word: once the solvers have read their options, unused_options() names those of `options`
// that none of them used, for the caller to report as an input error.
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"

namespace suite {

class PetscSession {
 public:
  explicit PetscSession(const mpi::Comm& comm, const std::string& options = "");
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  // The options of `options` (their names, "-drag_ksp_rtoll") that nothing has read so far.
  std::vector<std::string> unused_options() const;

 private:
  std::vector<std::string> names_;  // the option names in `options`
};

}  // namespace suite
