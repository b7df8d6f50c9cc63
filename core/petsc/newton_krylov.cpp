#include "core/petsc/newton_krylov.hpp"

#include <petscsnes.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "core/petsc/petsc_check.hpp"

namespace suite {

namespace {

// What the residual callback needs, and the first exception it caught (an exception must not
// cross PETSc's C frames: it is kept, the callback returns an error code, and solve() rethrows).
struct CallbackState {
  const NewtonKrylov::Residual* residual = nullptr;
  std::exception_ptr failure;
  int evaluations = 0;
};

PetscErrorCode evaluate(SNES snes, ::Vec x, ::Vec r, void* context) {
  auto& state = *static_cast<CallbackState*>(context);
  const PetscScalar* in = nullptr;
  PetscScalar* out = nullptr;
  PetscCall(VecGetArrayRead(x, &in));
  PetscCall(VecGetArray(r, &out));
  try {
    ++state.evaluations;
    if (!(*state.residual)(in, out)) PetscCall(SNESSetFunctionDomainError(snes));
  } catch (...) {
    if (!state.failure) state.failure = std::current_exception();
  }
  PetscCall(VecRestoreArray(r, &out));
  PetscCall(VecRestoreArrayRead(x, &in));
  return state.failure ? PETSC_ERR_USER : 0;
}

// The history's room: the most Newton iterations an options database may ask for.
constexpr int kMostIterations = 1000;

// Frees the solve's PETSc objects however it ends (return codes ignored: this only releases memory).
struct Objects {
  SNES snes = nullptr;
  ::Mat jacobian = nullptr;
  ::Vec x = nullptr, r = nullptr;
  ~Objects() {
    MatDestroy(&jacobian);
    VecDestroy(&x);
    VecDestroy(&r);
    SNESDestroy(&snes);
  }
};

}  // namespace

NewtonKrylov::NewtonKrylov(const mpi::Comm& comm, NewtonKrylovSettings settings)
    : comm_(comm), settings_(std::move(settings)) {}

NewtonKrylovStats NewtonKrylov::solve(std::vector<double>& x, const Residual& residual) {
  static_assert(sizeof(PetscScalar) == sizeof(double), "PETSc must be built with real double scalars");
  CallbackState state{&residual, nullptr, 0};
  Objects o;
  const auto local = static_cast<PetscInt>(x.size());
  SUITE_PETSC_CHECK(VecCreateMPI(comm_.raw(), local, PETSC_DETERMINE, &o.x));
  SUITE_PETSC_CHECK(VecDuplicate(o.x, &o.r));
  PetscInt global = 0;
  SUITE_PETSC_CHECK(VecGetSize(o.x, &global));
  {
    PetscScalar* values = nullptr;
    SUITE_PETSC_CHECK(VecGetArray(o.x, &values));
    std::copy(x.begin(), x.end(), values);
    SUITE_PETSC_CHECK(VecRestoreArray(o.x, &values));
  }
  SUITE_PETSC_CHECK(SNESCreate(comm_.raw(), &o.snes));
  SUITE_PETSC_CHECK(SNESSetOptionsPrefix(o.snes, settings_.prefix.c_str()));
  SUITE_PETSC_CHECK(SNESSetType(o.snes, SNESNEWTONLS));
  SUITE_PETSC_CHECK(SNESSetFunction(o.snes, o.r, evaluate, &state));
  SUITE_PETSC_CHECK(MatCreateSNESMF(o.snes, &o.jacobian));
  SUITE_PETSC_CHECK(SNESSetJacobian(o.snes, o.jacobian, o.jacobian, MatMFFDComputeJacobian, nullptr));
  const double atol = settings_.atol_per_entry * std::sqrt(static_cast<double>(std::max<PetscInt>(global, 1)));
  SUITE_PETSC_CHECK(SNESSetTolerances(o.snes, atol, settings_.rtol, 0.0, 50, 100000));
  // A linear solve that stalls (GMRES on differences carrying ~1e-8 errors, once R is small)
  // still gives a direction: the line search judges it, and the norm decides convergence.
  SUITE_PETSC_CHECK(SNESSetMaxLinearSolveFailures(o.snes, 50));
  KSP ksp = nullptr;
  PC pc = nullptr;
  SUITE_PETSC_CHECK(SNESGetKSP(o.snes, &ksp));
  SUITE_PETSC_CHECK(KSPSetType(ksp, KSPGMRES));
  SUITE_PETSC_CHECK(KSPSetTolerances(ksp, settings_.krylov_rtol, 1e-50, PETSC_DEFAULT, 1000));
  SUITE_PETSC_CHECK(KSPGetPC(ksp, &pc));
  SUITE_PETSC_CHECK(PCSetType(pc, PCNONE));
  std::vector<PetscReal> norms(kMostIterations + 1);
  std::vector<PetscInt> inner(norms.size());
  SUITE_PETSC_CHECK(
      SNESSetConvergenceHistory(o.snes, norms.data(), inner.data(), static_cast<PetscInt>(norms.size()), PETSC_TRUE));
  SUITE_PETSC_CHECK(SNESSetFromOptions(o.snes));
  const PetscErrorCode rc = SNESSolve(o.snes, nullptr, o.x);
  if (state.failure) std::rethrow_exception(state.failure);
  SUITE_PETSC_CHECK(rc);

  NewtonKrylovStats stats;
  PetscInt its = 0, linear = 0;
  SNESConvergedReason reason{};
  SUITE_PETSC_CHECK(SNESGetIterationNumber(o.snes, &its));
  SUITE_PETSC_CHECK(SNESGetLinearSolveIterations(o.snes, &linear));
  SUITE_PETSC_CHECK(SNESGetConvergedReason(o.snes, &reason));
  stats.newton_iterations = static_cast<int>(its);
  stats.krylov_iterations = static_cast<int>(linear);
  stats.residual_evaluations = state.evaluations;
  stats.converged = reason > 0;
  stats.reason = SNESConvergedReasons[reason];
  {
    PetscInt n = 0;
    PetscReal* a = nullptr;
    SUITE_PETSC_CHECK(SNESGetConvergenceHistory(o.snes, &a, nullptr, &n));
    stats.history.assign(a, a + n);
  }
  const PetscScalar* values = nullptr;
  SUITE_PETSC_CHECK(VecGetArrayRead(o.x, &values));
  std::copy(values, values + local, x.begin());
  SUITE_PETSC_CHECK(VecRestoreArrayRead(o.x, &values));
  return stats;
}

}  // namespace suite
