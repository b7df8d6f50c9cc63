#pragma once
// One PETSc session for a whole test program (PETSc is initialised once per process), on a
// duplicate of the world so that the tests' messages stay apart from anyone else's. Register it
// once per program:
//   PetscEnvironment* const environment = suite::testing::add_petsc_environment("-drag_ksp_rtol 1e-14");
// and reach the communicator with environment->comm().
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

#include "core/mpi/comm.hpp"
#include "core/petsc/petsc_session.hpp"

namespace suite::testing {

class PetscEnvironment : public ::testing::Environment {
 public:
  explicit PetscEnvironment(std::string options) : options_(std::move(options)) {}
  void SetUp() override {
    comm_ = std::make_unique<mpi::Comm>(mpi::Comm(MPI_COMM_WORLD).dup());
    session_ = std::make_unique<PetscSession>(*comm_, options_);
  }
  void TearDown() override {
    session_.reset();
    comm_.reset();
  }
  const mpi::Comm& comm() const { return *comm_; }

 private:
  std::string options_;
  std::unique_ptr<mpi::Comm> comm_;
  std::unique_ptr<PetscSession> session_;
};

// Registers a PETSc environment with the options-database string `options` (gtest owns it).
inline PetscEnvironment* add_petsc_environment(const std::string& options = "") {
  return static_cast<PetscEnvironment*>(::testing::AddGlobalTestEnvironment(new PetscEnvironment(options)));
}

}  // namespace suite::testing
