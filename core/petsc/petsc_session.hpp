#pragma once
// PetscInitialize/PetscFinalize on an explicit communicator (PETSC_COMM_WORLD is set to it
// first), after MPI is up. PETSc errors are returned as codes (no traceback printed), so they
// reach check_petsc. `options` is an options-database string such as
// "-mpm_ksp_type cg -mpm_ksp_rtol 1e-10", usually taken from a scene's petsc: section; the
// PETSC_OPTIONS environment variable is read as well. COLLECTIVE on `comm`.
#include <string>

#include "core/mpi/comm.hpp"

namespace suite {

class PetscSession {
 public:
  explicit PetscSession(const mpi::Comm& comm, const std::string& options = "");
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
};

}  // namespace suite
