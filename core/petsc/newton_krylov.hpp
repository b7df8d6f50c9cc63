#pragma once
// Matrix-free Newton-Krylov for a nonlinear system R(x) = 0 distributed over a communicator,
// through PETSc SNES: Newton with a backtracking line search (SNESNEWTONLS), each Newton step's
// linear system J dx = -R solved by GMRES, and J applied by finite differences of R
// (J w ~ (R(x + e w) - R(x)) / e, PETSc's MatMFFD) so no Jacobian is ever assembled. Each rank
// holds `local_size` entries of x and R, in its own order (only the residual function reads
// them); the residual function is COLLECTIVE (every rank calls it the same number of times) and
// may exchange halos.
//
// Defaults (NewtonKrylovSettings; the options database overrides them through the prefix, e.g.
// -implicit_snes_rtol, -implicit_ksp_rtol, -implicit_snes_max_it, -implicit_snes_ksp_ew,
// -implicit_snes_monitor): snes_atol atol_per_entry * sqrt(global size) (an RMS bound), snes_max_it
// 50, GMRES without a preconditioner (the caller scales R so that its Jacobian is near the
// identity).
//
// Must be used inside a suite::PetscSession. The header does not include PETSc (its Vec and Mat
// would clash with mpm2grid's Eigen templates).
#include <functional>
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"

namespace suite {

struct NewtonKrylovSettings {
  std::string prefix;  // the options database prefix (mpm2grid's implicit forces: "implicit_")
  double atol_per_entry = 1e-12;     // the absolute residual bound, per entry (RMS)
  double rtol = 1e-6;                // the residual bound relative to the initial guess's
  double krylov_rtol = 1e-3;         // each Newton step's linear solve, relative
};

struct NewtonKrylovStats {
  int newton_iterations = 0;
  int krylov_iterations = 0;     // summed over the Newton iterations
  int residual_evaluations = 0;  // on this rank, finite-difference products included
  bool converged = false;
  std::string reason;           // PETSc's converged or diverged reason, e.g. "CONVERGED_FNORM_RELATIVE"
  std::vector<double> history;  // ||R(x_k)||, k = 0 .. newton_iterations
};

class NewtonKrylov {
 public:
  // r = R(x): both spans have local_size entries. Returns false where x lies outside R's domain
  // (the same answer on every rank): the line search then shortens its step.
  using Residual = std::function<bool(const double* x, double* r)>;

  NewtonKrylov(const mpi::Comm& comm, NewtonKrylovSettings settings = {});

  // Solves R(x) = 0 from the initial guess in x (local_size entries, overwritten with the
  // solution). A residual function that throws stops the solve and the exception comes out here
  // (every rank's function must then throw, or the others wait). COLLECTIVE.
  NewtonKrylovStats solve(std::vector<double>& x, const Residual& residual);

 private:
  mpi::Comm comm_;
  NewtonKrylovSettings settings_;
};

}  // namespace suite
