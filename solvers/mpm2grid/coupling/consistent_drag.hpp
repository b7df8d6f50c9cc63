#pragma once
// The drag-coupled grid velocity update with the consistent drag matrix (docs/methods/mpm2grid.md,
// "Discretization", step 3), solved with PETSc. Per velocity component, on the nodes where both
// species have mass (the "coupled" nodes),
//   [ M_s + dt D   -dt D      ] [v_s]   [b_s]
//   [ -dt D        M_w + dt D ] [v_w] = [b_w],     b_a = (m v)_a + dt f_a (f including gravity),
// with M_a = diag(m_a,i) and D_ij = sum over soil particles p of (c_E V)_p N_i(x_p) N_j(x_p),
// i and j both coupled (a particle's share on a node that is not coupled is dropped, as the
// lumped form couples only where both species have mass). The matrix is
// blockdiag(M_s, M_w) + dt D (x) [[1, -1], [-1, 1]], a positive diagonal plus a Kronecker product
// of two positive semi-definite matrices: symmetric positive definite for every dt >= 0. Its
// column sums of the drag terms cancel, so the exact solution conserves the total momentum
// sum_i (m_s v_s + m_w v_w) = sum_i (b_s + b_w) for any dt (unconditionally stable: the drag only
// takes kinetic energy out). The row sums of D are the lumped coefficients d_i of
// coupling/drag_solve.hpp (where every node the particles touch is coupled); where the relative
// velocity is uniform and m_s,i / d_i and m_w,i / d_i are the same on every node, both forms give
// the same velocities. On the other nodes the update is node-local without drag: v = b / m, or 0
// without mass.
//
// Unknowns: coupled node g (a global index over all ranks) has rows 2 g (soil) and 2 g + 1
// (water), so a rank's rows are one contiguous range and a node's two unknowns stay together.
// The matrix is preallocated from the stencil: a node couples only to nodes within 3 spacings
// per axis (two overlapping 4-wide stencils).
// One matrix serves the Dim components: it is assembled once per call and solved for Dim
// right-hand sides. Each rank adds its own soil particles' drag terms; the rows another rank
// holds are summed here row by row and sent to that rank (decomposition/exchange.hpp's
// all_to_all), which adds them to its own, so PETSc's assembly has no entries to move (its stash
// sent every entry with its indices, found the receivers with a collective and sorted the
// entries on both sides: on 2 ranks 2.5-4.7 times the cost of this exchange, docs/mpm2grid.md,
// "Benchmarks"). No rank ever holds the global vector.
//
// Which rank holds a row in the solve (DragRows): the coupled nodes gather where the water meets
// the soil, in few of the particles' parts (over the first 60 steps of example 2 at h = 0.025 m
// on 16 ranks one rank owns 507 of the 1,019), and every rank waits for the busiest at each
// Krylov iteration's reductions. `owners` solves each row on the node's owner (no traffic
// beyond the solve's own). `balanced` gives each rank an equal contiguous share of the
// global numbering, whoever owns the nodes: the owners still assemble their nodes' rows (and
// send those another rank holds) and hold their right-hand sides and velocities, which reach the
// solve's layout and come back by one VecScatter (docs/mpm2grid.md, "Benchmarks", for what each
// costs on 2 ranks; at 16 ranks it is unmeasured). The global numbering and so the
// matrix are the same in both; the Krylov iterations differ by round-off (the reductions' order
// follows the layout), and their number with a preconditioner that works on each rank's rows.
// `automatic` (the scenes' default) chooses between the two at each call from the owned counts.
// The other way to spread the rows, the nodes themselves over the ranks, is the partition's:
// decomposition.balance_wet_soil (decomposition/partition.hpp).
//
// PETSc: a ConsistentDrag must be created and destroyed inside a suite::PetscSession (it owns a
// KSP, freed in the destructor, which must run before PetscFinalize). Defaults: KSPCG, PCSOR
// (PETSc's default sweep: one symmetric Gauss-Seidel sweep over each rank's rows, an SPD
// preconditioner for any SPD matrix), rtol 1e-12 on the unpreconditioned residual norm (so
// ||b - A v|| <= rtol ||b||, which bounds the momentum error), atol 1e-50, zero initial guess; the
// options database overrides them through the prefix, e.g. -drag_ksp_type, -drag_pc_type,
// -drag_ksp_rtol, -drag_ksp_max_it. Against point Jacobi (PCJACOBI, the default before
// 2026-11-28) on example 2 at h = 0.025 m: 13 CG iterations a component instead of 37 on one
// rank, 15 on 2 ranks, 17 on 16, each about three matrix-vector products' work instead of one:
// a third of the Krylov solve's reductions and halo exchanges for about the same arithmetic
// (docs/mpm2grid.md, "Benchmarks"). Incomplete Cholesky blocks (-drag_pc_type bjacobi) took 4
// to 13 but are not safe here: the matrix is not an M-matrix (D couples a species' nodes with
// positive entries), and in 3D at dt = 1000 tau_d ICC(0) had a negative pivot and, shifted, CG
// stalled. The matrix has block size 2, so -drag_pc_type pbjacobi inverts each node's 2 x 2
// block.
//
// The header does not include PETSc: its global Vec and Mat would clash with mpm2grid's Eigen
// Vec<Dim> and Mat<Dim> wherever both namespaces are open. The PETSc objects live in the .cpp.
#include <memory>
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"
#include "solvers/mpm2grid/decomposition/wait_clock.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"

namespace suite::mpm2grid {

// Both species have mass on the node: the node's velocities are coupled by the drag.
inline bool drag_coupled(double soil_mass, double water_mass) {
  return soil_mass > 0 && water_mass > 0;
}

// The coupled nodes' global unknown numbers. global[slot] for every node slot of this rank's
// grid: the node's index g among the coupled nodes of all ranks (rows 2 g and 2 g + 1), or -1
// when the node is not coupled (it gets the node-local update). This rank owns g in
// [first, first + owned); the owned ranges of the ranks follow each other in rank order
// (first = the sum of the lower ranks' owned counts). A slot whose g another rank owns is a
// ghost: this rank may add drag terms to its rows, and its velocity is left as it was (the
// owner computes it). Every owned g must appear on exactly one slot of this rank's grid, and
// ranks sharing a node must give it the same g.
// The global count of unknowns (2 per coupled node) must fit PETSc's index type.
struct NodeNumbering {
  std::vector<long> global;  // per node slot: coupled-node index, or -1
  long owned = 0;            // coupled nodes this rank owns
  long first = 0;            // global index of this rank's first owned node

  bool owns(long g) const { return g >= first && g < first + owned; }

  // This rank owns every coupled node of its grid (today's case: one rank, or ranks whose grids
  // share no node). Numbers the coupled slots in slot order after the lower ranks' nodes
  // (MPI_Exscan of the owned counts). COLLECTIVE on comm.
  template <int Dim>
  static NodeNumbering own_all(const mpi::Comm& comm, const NodeFields<Dim>& soil, const NodeFields<Dim>& water);
  // This rank owns the coupled nodes of the blocks marked in owned_block (one flag per block of
  // 4^Dim or kNodes slots) and numbers them in slot order after the lower ranks' nodes; the other
  // slots get -1, to be replaced by their owners' numbers (a halo copy). COLLECTIVE on comm.
  template <int Dim>
  static NodeNumbering own_blocks(const mpi::Comm& comm, const NodeFields<Dim>& soil, const NodeFields<Dim>& water,
                                  const std::vector<char>& owned_block);
};

// Where the solve's rows go: with the nodes' owners, in equal shares over the ranks, or
// (automatic) in equal shares where the busiest owner holds more than 1.2 times the mean coupled
// nodes, else with the owners (consistent_drag.cpp, kUnevenOwners).
enum class DragRows { owners, balanced, automatic };

// What one solve did, over the Dim components.
struct SolveStats {
  long unknowns = 0;         // rows of the global system (2 x coupled nodes)
  long owned_nodes = 0;      // the coupled nodes this rank owns (its share of the assembly)
  long solved_nodes = 0;     // the coupled nodes whose rows this rank holds in the Krylov solve
  int iterations = 0;        // most Krylov iterations of a component
  double residual_norm = 0;  // largest final residual norm of a component (the KSP's norm type)
  int reason = 0;            // PETSc's KSPConvergedReason of the component with the most iterations
  std::string reason_name;   // its name, e.g. "CONVERGED_RTOL"
  // This rank's wall seconds: computing and inserting its rows (with the vectors' setup and the
  // preallocation; with DragRows::balanced the counts' scatter too), the assembly's exchange
  // (the rows for other ranks sent, theirs received and added, PETSc's assembly, and the waiting
  // for the slowest: a rank with few rows waits here), and the Krylov solves of the Dim
  // components with their right-hand sides, solutions and scatters.
  double rows_s = 0, exchange_s = 0, krylov_s = 0;
};

template <int Dim>
class ConsistentDrag {
 public:
  // COLLECTIVE on comm. Creates the KSP with the defaults above, then reads the options database
  // under `prefix`.
  explicit ConsistentDrag(const mpi::Comm& comm, const std::string& prefix = "drag_", DragRows rows = DragRows::owners);
  ~ConsistentDrag();
  ConsistentDrag(const ConsistentDrag&) = delete;
  ConsistentDrag& operator=(const ConsistentDrag&) = delete;

  // Sets soil_nodes.velocity and water_nodes.velocity: on this rank's owned coupled nodes the
  // solution of the block system, on the slots numbered -1 the node-local update without drag,
  // on ghost slots nothing. soil: this rank's soil particles, soil_drag their (c_E V)_p in kg/s
  // (one per particle); their stencils must lie in `grid`. The node fields hold mass, momentum
  // and force (gravity included) for every slot of `grid`; on owned nodes they must be complete
  // (summed over ranks). groups: the soil particles' groups (the block holding each stencil's
  // first node: touch_blocks, find_groups), found here when null. wait: where given, the time
  // blocked in this call's own collectives (the counts' gather, the input check, the rows sent
  // to other ranks; not PETSc's, whose reductions it cannot see) is counted on it. COLLECTIVE on
  // the comm. Throws LibraryError naming the prefix and PETSc's reason when the Krylov solve
  // diverges, std::invalid_argument on inconsistent sizes.
  SolveStats solve(const BlockGrid<Dim>& grid, const Particles<Dim>& soil, const std::vector<double>& soil_drag,
                   NodeFields<Dim>& soil_nodes, NodeFields<Dim>& water_nodes, double dt, const NodeNumbering& numbering,
                   const std::vector<int>* groups = nullptr, WaitClock* wait = nullptr);

  const std::string& prefix() const { return prefix_; }

 private:
  struct Layouts;
  void prepare_vectors(const Layouts& layouts);
  // Returns the seconds spent in PETSc's MatAssemblyBegin/End.
  double assemble(const BlockGrid<Dim>& grid, const Particles<Dim>& soil, const std::vector<double>& soil_drag,
                  const NodeFields<Dim>& soil_nodes, const NodeFields<Dim>& water_nodes, double dt,
                  const NodeNumbering& numbering, const std::vector<long>& owned_slots, const Layouts& layouts,
                  const std::vector<int>* groups, WaitClock* wait);

  struct Petsc;  // the KSP, the matrix (rebuilt every call: the pattern follows the particles),
                 // the vectors and the scatter (kept while every rank's counts stay the same)
  mpi::Comm comm_;
  std::string prefix_;
  DragRows rows_;
  std::unique_ptr<Petsc> petsc_;
};

extern template class ConsistentDrag<2>;
extern template class ConsistentDrag<3>;
extern template NodeNumbering NodeNumbering::own_all<2>(const mpi::Comm&, const NodeFields<2>&, const NodeFields<2>&);
extern template NodeNumbering NodeNumbering::own_all<3>(const mpi::Comm&, const NodeFields<3>&, const NodeFields<3>&);
extern template NodeNumbering NodeNumbering::own_blocks<2>(const mpi::Comm&, const NodeFields<2>&, const NodeFields<2>&,
                                                           const std::vector<char>&);
extern template NodeNumbering NodeNumbering::own_blocks<3>(const mpi::Comm&, const NodeFields<3>&, const NodeFields<3>&,
                                                           const std::vector<char>&);

}  // namespace suite::mpm2grid
