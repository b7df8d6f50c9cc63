// PETSc on an explicit communicator, options from a string, and error codes turned into
// messages. The solve is the 1D Laplacian tridiag(-1, 2, -1) x = 1, whose exact solution is
// x_i = (i+1)(n-i)/2; CG in exact arithmetic converges in n/2 iterations for this system.
#include <gtest/gtest.h>
#include <petscksp.h>

#include "core/errors.hpp"
#include "core/petsc/petsc_check.hpp"
#include "core/petsc/petsc_session.hpp"

namespace {

TEST(Petsc, SessionOnACommunicatorSolvesAndReportsErrors) {
  suite::mpi::Comm world(MPI_COMM_WORLD);
  auto comm = world.dup();
  suite::PetscSession session(comm, "-t_ksp_type cg -t_pc_type jacobi -t_ksp_rtol 1e-13 -t_ksp_rtoll -1e-3");
  const PetscInt n = 64;
  Mat A;
  Vec x, b;
  KSP ksp;
  SUITE_PETSC_CHECK(MatCreateAIJ(comm.raw(), PETSC_DECIDE, PETSC_DECIDE, n, n, 3, nullptr, 1, nullptr, &A));
  PetscInt lo, hi;
  SUITE_PETSC_CHECK(MatGetOwnershipRange(A, &lo, &hi));
  for (PetscInt i = lo; i < hi; ++i) {
    if (i > 0) SUITE_PETSC_CHECK(MatSetValue(A, i, i - 1, -1.0, INSERT_VALUES));
    SUITE_PETSC_CHECK(MatSetValue(A, i, i, 2.0, INSERT_VALUES));
    if (i < n - 1) SUITE_PETSC_CHECK(MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES));
  }
  SUITE_PETSC_CHECK(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  SUITE_PETSC_CHECK(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  SUITE_PETSC_CHECK(MatCreateVecs(A, &x, &b));
  SUITE_PETSC_CHECK(VecSet(b, 1.0));
  SUITE_PETSC_CHECK(KSPCreate(comm.raw(), &ksp));
  SUITE_PETSC_CHECK(KSPSetOptionsPrefix(ksp, "t_"));
  SUITE_PETSC_CHECK(KSPSetOperators(ksp, A, A));
  SUITE_PETSC_CHECK(KSPSetFromOptions(ksp));
  SUITE_PETSC_CHECK(KSPSolve(ksp, b, x));
  KSPType type;
  SUITE_PETSC_CHECK(KSPGetType(ksp, &type));
  EXPECT_STREQ(type, KSPCG) << "options string reached the options database";
  // The misspelt option (and its negative value, not an option name) is the only one unused.
  EXPECT_EQ(session.unused_options(), std::vector<std::string>{"-t_ksp_rtoll"});
  const PetscScalar* xa;
  SUITE_PETSC_CHECK(VecGetArrayRead(x, &xa));
  for (PetscInt i = lo; i < hi; ++i) {
    const double exact = 0.5 * double(i + 1) * double(n - i);
    EXPECT_NEAR(xa[i - lo], exact, 1e-9 * exact);  // rtol 1e-13 times cond(A) ~ 4n^2/pi^2
  }
  SUITE_PETSC_CHECK(VecRestoreArrayRead(x, &xa));
  // A wrong call comes back as a LibraryError naming it and PETSc's reason, not an abort.
  try {
    SUITE_PETSC_CHECK(KSPSetType(ksp, "no_such_solver"));
    ADD_FAILURE() << "an unknown KSP type was accepted";
  } catch (const suite::LibraryError& e) {
    EXPECT_NE(std::string(e.what()).find("PETSc call KSPSetType(ksp, \"no_such_solver\") failed"), std::string::npos)
        << e.what();
  }
  KSPDestroy(&ksp);
  VecDestroy(&x);
  VecDestroy(&b);
  MatDestroy(&A);
}

}  // namespace
