#include "core/petsc/petsc_session.hpp"

#include "core/petsc/petsc_check.hpp"

namespace suite {

PetscSession::PetscSession(const mpi::Comm& comm, const std::string& options) {
  PETSC_COMM_WORLD = comm.raw();
  SUITE_PETSC_CHECK(PetscInitializeNoArguments());
  SUITE_PETSC_CHECK(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  if (!options.empty()) SUITE_PETSC_CHECK(PetscOptionsInsertString(nullptr, options.c_str()));
}

PetscSession::~PetscSession() {
  PetscPopErrorHandler();
  PetscFinalize();
}

}  // namespace suite
