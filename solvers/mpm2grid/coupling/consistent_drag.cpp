#include "solvers/mpm2grid/coupling/consistent_drag.hpp"

#include <fmt/format.h>
#include <petscksp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/petsc/petsc_check.hpp"
#include "solvers/mpm2grid/decomposition/exchange.hpp"
#include "solvers/mpm2grid/transfer/apic.hpp"

namespace suite::mpm2grid {

// The two layouts of the global node numbering, as starts per rank (ranks + 1 entries, rank r
// holds nodes starts[r] .. starts[r + 1] - 1): where the owners hold the nodes (their right-hand
// sides and velocities: NodeNumbering's first and owned) and where the Krylov solve holds their
// rows. `same` when the two coincide (one rank, DragRows::owners, or equal shares by chance).
// DragRows::automatic takes equal shares where the busiest owner holds more than kUnevenOwners
// times the mean: equal shares cut the coupled region along the numbering rather than the
// geometry, which costs SOR about a fifth more CG iterations (example 2 at 0.025 m: 20 against
// 17 on 2 ranks, 28 against 26 on 16, with the wet soil balanced; two_species_3d at 5 mm: 18
// against 15), so they pay only where the owners' Krylov rows are more uneven than that (on 2
// ranks from rest to 3 s at 0.1 m, owners 1.39x the mean: the step 25.9 -> 24.7 s; in 3D at
// 1.05x: 3.40 -> 3.59 s). The choice follows the owned counts alone, the same on every rank
// and after a restart.
constexpr double kUnevenOwners = 1.2;

template <int Dim>
struct ConsistentDrag<Dim>::Layouts {
  std::vector<long> owners, solve;
  bool same = true;

  Layouts(const std::vector<long long>& owned, DragRows rows) : owners(owned.size() + 1, 0) {
    for (std::size_t r = 0; r < owned.size(); ++r) owners[r + 1] = owners[r] + static_cast<long>(owned[r]);
    const long ranks = static_cast<long>(owned.size());
    bool shares = rows == DragRows::balanced;
    if (rows == DragRows::automatic) {
      const long most = static_cast<long>(*std::max_element(owned.begin(), owned.end()));
      shares = static_cast<double>(most) * static_cast<double>(ranks) > kUnevenOwners * static_cast<double>(total());
    }
    if (!shares) {
      solve = owners;
    } else {
      solve.resize(owners.size());
      for (long r = 0; r <= ranks; ++r) solve[static_cast<std::size_t>(r)] = total() * r / ranks;
    }
    same = solve == owners;
  }
  long total() const { return owners.back(); }
  long solve_count(int rank) const {
    return solve[static_cast<std::size_t>(rank) + 1] - solve[static_cast<std::size_t>(rank)];
  }
  // The rank whose solve share holds node g (ranks with empty shares are passed over).
  int solve_rank(long g) const {  // solve[0] = 0 <= g < total
    return static_cast<int>(std::upper_bound(solve.begin(), solve.end(), g) - solve.begin()) - 1;
  }
  // The first and one past the last node of the solve's share holding node g.
  std::pair<long, long> solve_share(long g) const {
    const auto r = static_cast<std::size_t>(solve_rank(g));
    return {solve[r], solve[r + 1]};
  }
};

// The PETSc objects. Mat and Vec are PETSc's here (::), not mpm2grid's Eigen templates.
template <int Dim>
struct ConsistentDrag<Dim>::Petsc {
  KSP ksp = nullptr;
  ::Mat matrix = nullptr;
  ::Vec rhs = nullptr, solution = nullptr;  // the solve's layout
  ::Vec owner_side = nullptr;               // the owners' layout, where it differs
  VecScatter scatter = nullptr;             // owner_side -> the solve's layout (forward)
  std::vector<long> owners;                 // the owners' starts of the last solve (empty: none yet)

  Petsc() = default;
  Petsc(const Petsc&) = delete;
  Petsc& operator=(const Petsc&) = delete;
  ~Petsc() {
    // Return codes ignored: a destructor cannot throw, and these only release memory.
    MatDestroy(&matrix);
    VecScatterDestroy(&scatter);
    VecDestroy(&owner_side);
    VecDestroy(&rhs);
    VecDestroy(&solution);
    KSPDestroy(&ksp);
  }
};

namespace {

// One entry of a node row that another rank holds in the solve, summed over this rank's soil
// particles: the 2 x 2 block of rows 2 row, 2 row + 1 and columns 2 col, 2 col + 1 is
// [[soil_mass + drag, -drag], [-drag, water_mass + drag]] (drag = dt D; the masses only from the
// node's owner, on the diagonal). A rank sends its terms row by row, each row's columns in
// increasing order.
struct ShippedTerm {
  long row = 0, col = 0;
  double drag = 0, soil_mass = 0, water_mass = 0;
};

// The node row pair of `terms` (one row, columns increasing) into the matrix, added.
void add_node_rows(::Mat matrix, const ShippedTerm* terms, std::size_t n, std::vector<PetscInt>& cols,
                   std::vector<PetscScalar>& values) {
  const std::size_t width = 2 * n;
  cols.resize(width);
  values.resize(2 * width);
  for (std::size_t c = 0; c < n; ++c) {
    const ShippedTerm& t = terms[c];
    cols[2 * c] = static_cast<PetscInt>(2 * t.col);
    cols[2 * c + 1] = static_cast<PetscInt>(2 * t.col + 1);
    values[2 * c] = t.drag + t.soil_mass;  // soil row
    values[2 * c + 1] = -t.drag;
    values[width + 2 * c] = -t.drag;  // water row
    values[width + 2 * c + 1] = t.drag + t.water_mass;
  }
  const std::array<PetscInt, 2> rows{static_cast<PetscInt>(2 * terms[0].row),
                                     static_cast<PetscInt>(2 * terms[0].row + 1)};
  SUITE_PETSC_CHECK(
      MatSetValues(matrix, 2, rows.data(), static_cast<PetscInt>(width), cols.data(), values.data(), ADD_VALUES));
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

constexpr int ipow(int base, int exponent) {
  int v = 1;
  for (int i = 0; i < exponent; ++i) v *= base;
  return v;
}

// The node-local update without drag: v = b / m, or 0 without mass.
template <int Dim>
Vec<Dim> node_local_velocity(const NodeFields<Dim>& f, std::size_t slot, double dt) {
  const double m = f.mass[slot];
  return m > 0 ? Vec<Dim>((f.momentum[slot] + dt * f.force[slot]) / m) : Vec<Dim>::Zero();
}

// The blocks that hold a coupled node, where the matrix has its rows: list (in block order) and,
// for every block of the grid, its place in the list or -1.
struct CoupledBlocks {
  std::vector<int> list, place;
};

template <int Dim>
CoupledBlocks coupled_blocks(const BlockGrid<Dim>& grid, const NodeNumbering& numbering) {
  constexpr std::size_t kNodes = BlockGrid<Dim>::kNodes;
  CoupledBlocks c;
  c.place.assign(grid.blocks(), -1);
  for (std::size_t b = 0; b < grid.blocks(); ++b) {
    const long* g = numbering.global.data() + b * kNodes;
    if (std::any_of(g, g + kNodes, [](long n) { return n >= 0; })) {
      c.place[b] = static_cast<int>(c.list.size());
      c.list.push_back(static_cast<int>(b));
    }
  }
  return c;
}

// The node slots within 3 spacings of a node along every axis (its 7^Dim "window", x fastest):
// the nodes a drag entry can couple it to, since both must lie in one particle's 4-wide stencil.
// A window reaches at most one block further along each axis, so the 3^Dim neighbour blocks of
// every coupled block (the only ones with rows) are looked up once and the window is then walked
// with integer arithmetic.
template <int Dim>
class Windows {
 public:
  static constexpr int kSize = ipow(7, Dim);

  Windows(const BlockGrid<Dim>& grid, const CoupledBlocks& coupled) : coupled_(coupled), first_(coupled.list.size()) {
    for (std::size_t k = 0; k < coupled.list.size(); ++k)
      for (int n = 0; n < kNeighbours; ++n) {
        Index<Dim> corner;
        const Index<Dim>& block = grid.block_coord(static_cast<std::size_t>(coupled.list[k]));
        for (int d = 0, r = n; d < Dim; ++d, r /= 3) corner[d] = (block[d] + r % 3 - 1) * kSide;
        const int b = grid.block_of_node(corner);
        first_[k][static_cast<std::size_t>(n)] = b < 0 ? -1 : static_cast<long>(b) * kNodes;
      }
  }

  // out[n]: the slot of the window's node n (offset (n % 7 - 3, n / 7 % 7 - 3, ...) from the
  // node of `slot`, which lies in a coupled block), or -1 where the grid has no node. Per axis,
  // each of the 7 offsets gives a step between neighbour blocks and a place inside the block;
  // a window node adds them up (x fastest).
  void slots(long slot, std::array<long, kSize>& out) const {
    const auto& first = first_[static_cast<std::size_t>(coupled_.place[static_cast<std::size_t>(slot / kNodes)])];
    std::array<std::array<int, 7>, Dim> step, at;
    for (int d = 0, r = static_cast<int>(slot % kNodes), stride3 = 1, stride4 = 1; d < Dim;
         ++d, r /= kSide, stride3 *= 3, stride4 *= kSide)
      for (int o = 0; o < 7; ++o) {
        const int c = r % kSide + o - 3;  // -3 .. 6
        const int shift = c < 0 ? -1 : (c >= kSide ? 1 : 0);
        step[static_cast<std::size_t>(d)][static_cast<std::size_t>(o)] = (shift + 1) * stride3;
        at[static_cast<std::size_t>(d)][static_cast<std::size_t>(o)] = (c - shift * kSide) * stride4;
      }
    const auto put = [&](std::size_t n, int neighbour, int place) {
      const long block_first = first[static_cast<std::size_t>(neighbour)];
      out[n] = block_first < 0 ? -1 : block_first + place;
    };
    std::size_t n = 0;
    if constexpr (Dim == 2) {
      for (std::size_t y = 0; y < 7; ++y)
        for (std::size_t x = 0; x < 7; ++x) put(n++, step[1][y] + step[0][x], at[1][y] + at[0][x]);
    } else {
      for (std::size_t z = 0; z < 7; ++z)
        for (std::size_t y = 0; y < 7; ++y)
          for (std::size_t x = 0; x < 7; ++x)
            put(n++, step[2][z] + step[1][y] + step[0][x], at[2][z] + at[1][y] + at[0][x]);
    }
  }

 private:
  static constexpr int kSide = BlockGrid<Dim>::kSide, kNodes = BlockGrid<Dim>::kNodes;
  static constexpr int kNeighbours = ipow(3, Dim);
  const CoupledBlocks& coupled_;
  std::vector<std::array<long, kNeighbours>> first_;  // per coupled block: first slot of each
                                                      // neighbour block, or -1
};

// Upper bounds of the nonzero 2 x 2 blocks per owned node (block row, in global order), split as
// PETSc's preallocation wants them for the rank that holds the row in the solve: column nodes in
// that rank's share (d_nnz) and the others (o_nnz): the coupled nodes in the node's window (the
// node itself included, for the mass). Window nodes outside this rank's grid may be coupled nodes
// of another rank when there are several ranks; they count towards o_nnz, and towards d_nnz too
// where the solve's shares are not the owners' (such a node may then lie in the row's share).
template <int Dim, class Layouts>
void count_nonzeros(const Windows<Dim>& windows, const NodeNumbering& numbering, const std::vector<long>& owned_slots,
                    const Layouts& layouts, std::vector<PetscInt>& d_nnz, std::vector<PetscInt>& o_nnz) {
  d_nnz.assign(owned_slots.size(), 0);
  o_nnz.assign(owned_slots.size(), 0);
  const bool several_ranks = layouts.owners.size() > 2;
  std::array<long, Windows<Dim>::kSize> window;
  for (std::size_t k = 0; k < owned_slots.size(); ++k) {
    const auto [lo, hi] = layouts.solve_share(numbering.first + static_cast<long>(k));
    windows.slots(owned_slots[k], window);
    long own = 0, other = 0;
    for (const long slot : window) {
      if (slot < 0) {
        if (several_ranks) {
          ++other;
          if (!layouts.same) ++own;
        }
        continue;
      }
      const long g = numbering.global[static_cast<std::size_t>(slot)];
      if (g < 0) continue;
      if (g >= lo && g < hi)
        ++own;
      else
        ++other;
    }
    d_nnz[k] = static_cast<PetscInt>(std::min(own, hi - lo));
    o_nnz[k] = static_cast<PetscInt>(std::min(other, layouts.total() - (hi - lo)));
  }
}

// Adds c * (the stencil's weights of the 4^Dim nodes) to a node's window accumulator, where
// `origin` is the stencil's corner node minus the window's corner node (0 .. 3 per axis).
template <int Dim>
void add_stencil(const Stencil<Dim>& s, const Index<Dim>& origin, double c, double* acc) {
  if constexpr (Dim == 2) {
    for (int j = 0; j < 4; ++j) {
      const double cy = c * s.w[1][static_cast<std::size_t>(j)];
      double* row = acc + ((origin[1] + j) * 7 + origin[0]);
      for (int i = 0; i < 4; ++i) row[i] += cy * s.w[0][static_cast<std::size_t>(i)];
    }
  } else {
    for (int k = 0; k < 4; ++k) {
      const double cz = c * s.w[2][static_cast<std::size_t>(k)];
      for (int j = 0; j < 4; ++j) {
        const double cyz = cz * s.w[1][static_cast<std::size_t>(j)];
        double* row = acc + (((origin[2] + k) * 7 + origin[1] + j) * 7 + origin[0]);
        for (int i = 0; i < 4; ++i) row[i] += cyz * s.w[0][static_cast<std::size_t>(i)];
      }
    }
  }
}

}  // namespace

namespace {

// Numbers the coupled slots for which mine(slot) holds, in slot order after the lower ranks'.
template <int Dim, class Mine>
NodeNumbering number_coupled(const mpi::Comm& comm, const NodeFields<Dim>& soil, const NodeFields<Dim>& water,
                             Mine&& mine) {
  NodeNumbering numbering;
  numbering.global.assign(soil.mass.size(), -1);
  for (std::size_t i = 0; i < soil.mass.size(); ++i)
    if (mine(i) && drag_coupled(soil.mass[i], water.mass[i])) numbering.global[i] = numbering.owned++;
  numbering.first = static_cast<long>(comm.exclusive_prefix_sum(static_cast<long long>(numbering.owned)));
  for (auto& g : numbering.global)
    if (g >= 0) g += numbering.first;
  return numbering;
}

}  // namespace

template <int Dim>
NodeNumbering NodeNumbering::own_all(const mpi::Comm& comm, const NodeFields<Dim>& soil, const NodeFields<Dim>& water) {
  return number_coupled(comm, soil, water, [](std::size_t) { return true; });
}

template <int Dim>
NodeNumbering NodeNumbering::own_blocks(const mpi::Comm& comm, const NodeFields<Dim>& soil,
                                        const NodeFields<Dim>& water, const std::vector<char>& owned_block) {
  constexpr std::size_t kNodes = BlockGrid<Dim>::kNodes;
  if (owned_block.size() * kNodes != soil.mass.size())
    throw std::invalid_argument("NodeNumbering::own_blocks: one flag per block of the node fields expected");
  return number_coupled(comm, soil, water, [&](std::size_t i) { return owned_block[i / kNodes] != 0; });
}

template <int Dim>
ConsistentDrag<Dim>::ConsistentDrag(const mpi::Comm& comm, const std::string& prefix, DragRows rows)
    : comm_(comm), prefix_(prefix), rows_(rows), petsc_(std::make_unique<Petsc>()) {
  // Should a call below throw, petsc_ (a constructed member) still frees the KSP.
  KSP& ksp = petsc_->ksp;
  SUITE_PETSC_CHECK(KSPCreate(comm_.raw(), &ksp));
  SUITE_PETSC_CHECK(KSPSetOptionsPrefix(ksp, prefix_.c_str()));
  SUITE_PETSC_CHECK(KSPSetType(ksp, KSPCG));
  PC pc;
  SUITE_PETSC_CHECK(KSPGetPC(ksp, &pc));
  SUITE_PETSC_CHECK(PCSetType(pc, PCSOR));  // symmetric Gauss-Seidel on each rank's rows
  SUITE_PETSC_CHECK(KSPSetTolerances(ksp, 1e-12, 1e-50, PETSC_DEFAULT, PETSC_DEFAULT));
  SUITE_PETSC_CHECK(KSPSetFromOptions(ksp));
  // CG measures the preconditioned residual by default; the unpreconditioned one makes rtol a
  // bound on ||b - A v|| / ||b||, hence on the momentum error. Only where the options kept CG
  // and did not choose a norm themselves (other Krylov methods may not support this norm).
  KSPType type = nullptr;
  PetscBool cg = PETSC_FALSE, norm_set = PETSC_FALSE;
  SUITE_PETSC_CHECK(KSPGetType(ksp, &type));
  SUITE_PETSC_CHECK(PetscStrcmp(type, KSPCG, &cg));
  SUITE_PETSC_CHECK(PetscOptionsHasName(nullptr, prefix_.c_str(), "-ksp_norm_type", &norm_set));
  if (cg && !norm_set) SUITE_PETSC_CHECK(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
}

template <int Dim>
ConsistentDrag<Dim>::~ConsistentDrag() = default;

// The vectors of both layouts and the scatter between them, for this call's counts: kept while
// every rank's owned count is the same as at the last call (then so are both layouts), rebuilt
// otherwise, with the KSP's work vectors and preconditioner. Every rank decides alike (the
// counts are the same on all).
template <int Dim>
void ConsistentDrag<Dim>::prepare_vectors(const Layouts& layouts) {
  Petsc& p = *petsc_;
  if (layouts.owners == p.owners) return;
  SUITE_PETSC_CHECK(KSPReset(p.ksp));
  SUITE_PETSC_CHECK(VecScatterDestroy(&p.scatter));
  SUITE_PETSC_CHECK(VecDestroy(&p.owner_side));
  SUITE_PETSC_CHECK(VecDestroy(&p.rhs));
  SUITE_PETSC_CHECK(VecDestroy(&p.solution));
  const auto global = static_cast<PetscInt>(2 * layouts.total());
  const auto create = [&](long nodes, ::Vec& v) {
    SUITE_PETSC_CHECK(VecCreate(comm_.raw(), &v));
    SUITE_PETSC_CHECK(VecSetSizes(v, static_cast<PetscInt>(2 * nodes), global));
    SUITE_PETSC_CHECK(VecSetBlockSize(v, 2));
    SUITE_PETSC_CHECK(VecSetType(v, VECSTANDARD));
  };
  create(layouts.solve_count(comm_.rank()), p.rhs);
  SUITE_PETSC_CHECK(VecDuplicate(p.rhs, &p.solution));
  if (!layouts.same) {
    const auto r = static_cast<std::size_t>(comm_.rank());
    const long first = layouts.owners[r], owned = layouts.owners[r + 1] - first;
    create(owned, p.owner_side);
    // Each rank sends its owned nodes' entries to the same global places in the solve's layout.
    IS mine = nullptr;
    SUITE_PETSC_CHECK(
        ISCreateStride(PETSC_COMM_SELF, static_cast<PetscInt>(2 * owned), static_cast<PetscInt>(2 * first), 1, &mine));
    const PetscErrorCode created = VecScatterCreate(p.owner_side, mine, p.rhs, mine, &p.scatter);
    ISDestroy(&mine);
    SUITE_PETSC_CHECK(created);
  }
  p.owners = layouts.owners;
}

template <int Dim>
double ConsistentDrag<Dim>::assemble(const BlockGrid<Dim>& grid, const Particles<Dim>& soil,
                                     const std::vector<double>& soil_drag, const NodeFields<Dim>& soil_nodes,
                                     const NodeFields<Dim>& water_nodes, double dt, const NodeNumbering& numbering,
                                     const std::vector<long>& owned_slots, const Layouts& layouts,
                                     const std::vector<int>* groups, WaitClock* wait) {
  constexpr int kNodes = BlockGrid<Dim>::kNodes, kWindow = Windows<Dim>::kSize;
  Petsc& ps = *petsc_;
  ::Mat& matrix = ps.matrix;
  const auto local_rows = static_cast<PetscInt>(2 * layouts.solve_count(comm_.rank()));
  const auto global_rows = static_cast<PetscInt>(2 * layouts.total());
  const CoupledBlocks coupled = coupled_blocks(grid, numbering);
  const Windows<Dim> windows(grid, coupled);
  std::vector<PetscInt> d_nnz, o_nnz;
  count_nonzeros(windows, numbering, owned_slots, layouts, d_nnz, o_nnz);
  if (!layouts.same) {
    // The owners counted their nodes' rows; the solve's layout holds them: the counts travel the
    // way the right-hand sides do (exact as doubles).
    PetscScalar* v = nullptr;
    SUITE_PETSC_CHECK(VecGetArray(ps.owner_side, &v));
    for (std::size_t k = 0; k < d_nnz.size(); ++k) v[2 * k] = d_nnz[k], v[2 * k + 1] = o_nnz[k];
    SUITE_PETSC_CHECK(VecRestoreArray(ps.owner_side, &v));
    SUITE_PETSC_CHECK(VecScatterBegin(ps.scatter, ps.owner_side, ps.rhs, INSERT_VALUES, SCATTER_FORWARD));
    SUITE_PETSC_CHECK(VecScatterEnd(ps.scatter, ps.owner_side, ps.rhs, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* counts = nullptr;
    SUITE_PETSC_CHECK(VecGetArrayRead(ps.rhs, &counts));
    d_nnz.resize(static_cast<std::size_t>(local_rows / 2));
    o_nnz.resize(d_nnz.size());
    for (std::size_t k = 0; k < d_nnz.size(); ++k)
      d_nnz[k] = static_cast<PetscInt>(counts[2 * k]), o_nnz[k] = static_cast<PetscInt>(counts[2 * k + 1]);
    SUITE_PETSC_CHECK(VecRestoreArrayRead(ps.rhs, &counts));
  }

  SUITE_PETSC_CHECK(MatDestroy(&matrix));
  // AIJ with block size 2 (a node's soil and water rows): -drag_pc_type pbjacobi then inverts
  // each node's 2 x 2 block (the lumped drag coupling), and multigrid sees the layout.
  SUITE_PETSC_CHECK(MatCreate(comm_.raw(), &matrix));
  SUITE_PETSC_CHECK(MatSetSizes(matrix, local_rows, local_rows, global_rows, global_rows));
  SUITE_PETSC_CHECK(MatSetType(matrix, MATAIJ));
  SUITE_PETSC_CHECK(MatXAIJSetPreallocation(matrix, 2, d_nnz.empty() ? nullptr : d_nnz.data(),
                                            o_nnz.empty() ? nullptr : o_nnz.data(), nullptr, nullptr));

  // D row by row, so that PETSc receives each row once with its columns in increasing order
  // (adding a particle's 4^Dim x 4^Dim block at a time makes PETSc search and shift its rows for
  // every entry, far slower: docs/mpm2grid.md, "Benchmarks"). Only the soil particles whose
  // stencil reaches a coupled block add terms (at the start of example 2 those near the
  // reservoir's face: 1,019 coupled nodes against 248k soil particles at h = 0.025 m), and only
  // the coupled blocks have rows: the work follows the coupled nodes, not the grid or all the
  // particles. A stencil reaches the 2^Dim blocks from the one holding its first node (the
  // particle's group). First, for every node of the coupled blocks (row r = place of its block x
  // kNodes + its place in the block), the particles whose stencil holds it (compressed rows,
  // counted and then filled).
  std::vector<char> near(grid.blocks(), 0);  // blocks from which a stencil reaches a coupled block
  for (const int b : coupled.list)
    for (int corner = 0; corner < (1 << Dim); ++corner) {
      Index<Dim> from = grid.block_coord(static_cast<std::size_t>(b));
      for (int d = 0; d < Dim; ++d) from[d] -= (corner >> d) & 1;
      if (const int f = grid.find_block(from); f >= 0) near[static_cast<std::size_t>(f)] = 1;
    }
  const double h = grid.spacing();
  std::vector<int> found;
  if (!groups) {
    found.resize(soil.size());
    find_groups(soil, grid, ParticleRun{0, soil.size()}, found);
    groups = &found;
  }
  std::vector<std::size_t> reaching;  // the soil particles that add terms, in their order
  for (std::size_t p = 0; p < soil.size(); ++p) {
    const int group = (*groups)[p];
    if (group >= 0 && near[static_cast<std::size_t>(group)]) reaching.push_back(p);
  }
  const auto row_of = [&](long slot) {
    const int place = coupled.place[static_cast<std::size_t>(slot / kNodes)];
    return place < 0 || numbering.global[static_cast<std::size_t>(slot)] < 0
               ? -1L
               : static_cast<long>(place) * kNodes + slot % kNodes;
  };
  const std::size_t rows = coupled.list.size() * static_cast<std::size_t>(kNodes);
  std::vector<Stencil<Dim>> stencils;
  stencils.reserve(reaching.size());
  std::vector<std::size_t> start(rows + 1, 0);
  std::array<long, kNodes> slots;
  for (const std::size_t p : reaching) {
    stencils.emplace_back(soil.x[p], h);
    grid.stencil_slots(stencils.back(), slots);
    for (const long slot : slots)
      if (const long r = row_of(slot); r >= 0) ++start[static_cast<std::size_t>(r) + 1];
  }
  for (std::size_t r = 0; r < rows; ++r) start[r + 1] += start[r];
  std::vector<std::size_t> touching(start[rows]);  // places in `reaching`
  {
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < reaching.size(); ++k) {
      grid.stencil_slots(stencils[k], slots);
      for (const long slot : slots)
        if (const long r = row_of(slot); r >= 0) touching[next[static_cast<std::size_t>(r)]++] = k;
    }
  }

  // Then each coupled node i that this rank's particles touch or that this rank owns:
  // D_ij = sum_p (c_E V)_p N_i(x_p) N_j(x_p) over its window j, the masses on the diagonal where
  // i is owned, and the two rows 2 g_i (soil) and 2 g_i + 1 (water) with 2 x 2 blocks
  // [[m_s + dt D, -dt D], [-dt D, m_w + dt D]] (masses on j = i only). Columns of nodes that are
  // not coupled are dropped. Rows that another rank holds in the solve are sent to it, row by
  // row as summed here, and it adds them to its own (below): PETSc's stash would send every
  // entry with its row and column, find the receivers with a collective, and sort and merge the
  // entries on both sides (example 2 at 0.1 m from rest to 3 s on 2 ranks, the wet soil
  // balanced: the assembly's exchange 3.6 s of a 15.1 s grid solve through the stash, 1.5 s of
  // 12.8 s this way; 0.4 s where one rank holds every row).
  std::array<double, kWindow> acc;
  std::array<long, kWindow> window;
  std::vector<std::pair<long, double>> columns;  // (global node j, D_ij)
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> values;
  std::vector<ShippedTerm> terms;
  const int me = comm_.rank();
  std::vector<std::vector<ShippedTerm>> shipped(static_cast<std::size_t>(comm_.size()));
  for (std::size_t r = 0; r < rows; ++r) {
    const auto i = static_cast<std::size_t>(coupled.list[r / kNodes]) * kNodes + r % kNodes;  // slot
    const long gi = numbering.global[i];
    const bool owned = numbering.owns(gi);
    if (gi < 0 || (start[r] == start[r + 1] && !owned)) continue;
    const Index<Dim> node = grid.node_of(static_cast<long>(i));
    acc.fill(0.0);
    for (std::size_t t = start[r]; t < start[r + 1]; ++t) {
      const std::size_t k = touching[t];
      const Stencil<Dim>& s = stencils[k];
      Index<Dim> origin;
      double wi = 1;
      for (int d = 0; d < Dim; ++d) {
        const int o = node[d] - s.base[d];  // 0 .. 3: i lies in the stencil
        wi *= s.w[d][static_cast<std::size_t>(o)];
        origin[d] = 3 - o;
      }
      add_stencil<Dim>(s, origin, soil_drag[reaching[k]] * wi, acc.data());
    }
    windows.slots(static_cast<long>(i), window);
    columns.clear();
    for (int n = 0; n < kWindow; ++n) {
      const long slot = window[static_cast<std::size_t>(n)];
      const bool centre = n == (kWindow - 1) / 2;
      if (slot < 0 || (acc[static_cast<std::size_t>(n)] == 0 && !centre)) continue;
      const long gj = numbering.global[static_cast<std::size_t>(slot)];
      if (gj >= 0) columns.emplace_back(gj, acc[static_cast<std::size_t>(n)]);
    }
    std::sort(columns.begin(), columns.end());
    const double ms = owned ? soil_nodes.mass[i] : 0.0, mw = owned ? water_nodes.mass[i] : 0.0;
    const int holder = layouts.solve_rank(gi);
    std::vector<ShippedTerm>& out = holder == me ? terms : shipped[static_cast<std::size_t>(holder)];
    if (holder == me) terms.clear();
    for (const auto& [gj, d] : columns) out.push_back({gi, gj, dt * d, gj == gi ? ms : 0.0, gj == gi ? mw : 0.0});
    if (holder == me) add_node_rows(matrix, terms.data(), terms.size(), cols, values);
  }
  const Clock::time_point exchange_start = Clock::now();
  if (comm_.size() > 1) {
    // The rows from the other ranks, by source rank (so the sums' order does not depend on the
    // messages' timing), each row's run of terms added at once. Then no rank has entries for
    // another's rows, and PETSc's assembly skips its stash.
    const auto arrived = all_to_all(comm_, shipped, wait);
    for (std::size_t r = 0; r < arrived.size(); ++r) {
      if (static_cast<int>(r) == me) continue;
      const std::vector<ShippedTerm>& in = arrived[r];
      for (std::size_t a = 0, b = 0; a < in.size(); a = b) {
        for (b = a + 1; b < in.size() && in[b].row == in[a].row;) ++b;
        add_node_rows(matrix, in.data() + a, b - a, cols, values);
      }
    }
    SUITE_PETSC_CHECK(MatSetOption(matrix, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  }
  SUITE_PETSC_CHECK(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY));
  SUITE_PETSC_CHECK(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY));
  const double exchange_s = seconds_since(exchange_start);
  SUITE_PETSC_CHECK(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE));
  SUITE_PETSC_CHECK(MatSetOption(matrix, MAT_SPD, PETSC_TRUE));
  return exchange_s;
}

template <int Dim>
SolveStats ConsistentDrag<Dim>::solve(const BlockGrid<Dim>& grid, const Particles<Dim>& soil,
                                      const std::vector<double>& soil_drag, NodeFields<Dim>& soil_nodes,
                                      NodeFields<Dim>& water_nodes, double dt, const NodeNumbering& numbering,
                                      const std::vector<int>* groups, WaitClock* wait) {
  const std::size_t nodes = grid.nodes();
  // The owned slots in global order, and the checks. Every rank takes part in the same
  // collectives whatever it finds, and a problem on any rank stops every rank here rather than
  // leaving the others waiting inside PETSc.
  const long owned = numbering.owned;
  WaitClock unused;
  WaitClock& waited = wait ? *wait : unused;
  const Layouts layouts(waited.time([&] { return comm_.all_gather(static_cast<long long>(owned)); }), rows_);
  const long lower = layouts.owners[static_cast<std::size_t>(comm_.rank())], total = layouts.total();
  std::string problem;
  const auto sized = [&](const NodeFields<Dim>& f) {
    return f.mass.size() == nodes && f.momentum.size() == nodes && f.force.size() == nodes &&
           f.velocity.size() == nodes;
  };
  if (!sized(soil_nodes) || !sized(water_nodes) || numbering.global.size() != nodes)
    problem = fmt::format("node fields ({}, {} masses) and numbering ({}) must have one entry per grid node ({})",
                          soil_nodes.mass.size(), water_nodes.mass.size(), numbering.global.size(), nodes);
  else if (soil_drag.size() != soil.size())
    problem = fmt::format("{} drag coefficients for {} soil particles", soil_drag.size(), soil.size());
  else if (groups && groups->size() != soil.size())
    problem = fmt::format("{} groups for {} soil particles", groups->size(), soil.size());
  else if (!(dt >= 0))
    problem = fmt::format("dt = {} must be >= 0", dt);
  else if (owned < 0 || numbering.first != lower)
    problem = fmt::format("owned = {}, first = {}: first must be the sum of the lower ranks' owned counts ({})", owned,
                          numbering.first, lower);
  else if (2 * total > static_cast<long>(std::numeric_limits<PetscInt>::max()))
    problem =
        fmt::format("{} coupled nodes are more unknowns than PETSc's {}-bit indices hold", total, 8 * sizeof(PetscInt));
  std::vector<long> owned_slots;
  if (problem.empty()) {
    owned_slots.assign(static_cast<std::size_t>(owned), -1);
    for (std::size_t slot = 0; slot < nodes && problem.empty(); ++slot) {
      const long g = numbering.global[slot];
      if (g < -1 || g >= total) {
        problem = fmt::format("slot {} has node number {}, outside -1 .. {}", slot, g, total - 1);
      } else if (numbering.owns(g)) {
        long& at = owned_slots[static_cast<std::size_t>(g - numbering.first)];
        if (at >= 0) problem = fmt::format("owned node {} appears on slots {} and {}", g, at, slot);
        at = static_cast<long>(slot);
      }
    }
    for (std::size_t k = 0; k < owned_slots.size() && problem.empty(); ++k)
      if (owned_slots[k] < 0) problem = fmt::format("owned node {} is on no slot", numbering.first + k);
  }
  if (waited.time([&] { return comm_.any(!problem.empty()); }))
    throw std::invalid_argument(fmt::format("ConsistentDrag ({}): {}", prefix_,
                                            problem.empty() ? "inconsistent input on another rank" : problem));

  // Nodes that are not coupled: the node-local update.
  for (std::size_t slot = 0; slot < nodes; ++slot) {
    if (numbering.global[slot] >= 0) continue;
    soil_nodes.velocity[slot] = node_local_velocity(soil_nodes, slot, dt);
    water_nodes.velocity[slot] = node_local_velocity(water_nodes, slot, dt);
  }

  const Clock::time_point assembly_start = Clock::now();
  prepare_vectors(layouts);
  SolveStats stats;
  stats.exchange_s =
      assemble(grid, soil, soil_drag, soil_nodes, water_nodes, dt, numbering, owned_slots, layouts, groups, wait);
  Petsc& p = *petsc_;
  SUITE_PETSC_CHECK(KSPSetOperators(p.ksp, p.matrix, p.matrix));
  stats.rows_s = seconds_since(assembly_start) - stats.exchange_s;
  const Clock::time_point krylov_start = Clock::now();
  stats.unknowns = 2 * layouts.total();
  stats.owned_nodes = owned;
  stats.solved_nodes = layouts.solve_count(comm_.rank());
  // The owners' right-hand sides and velocities: in the solve's vectors where the layouts agree,
  // else in owner_side, scattered to and from the solve's layout.
  ::Vec at_owners = layouts.same ? p.rhs : p.owner_side;
  for (int d = 0; d < Dim; ++d) {
    PetscScalar* b = nullptr;
    SUITE_PETSC_CHECK(VecGetArray(at_owners, &b));
    for (std::size_t k = 0; k < owned_slots.size(); ++k) {
      const auto slot = static_cast<std::size_t>(owned_slots[k]);
      b[2 * k] = soil_nodes.momentum[slot][d] + dt * soil_nodes.force[slot][d];
      b[2 * k + 1] = water_nodes.momentum[slot][d] + dt * water_nodes.force[slot][d];
    }
    SUITE_PETSC_CHECK(VecRestoreArray(at_owners, &b));
    if (!layouts.same) {
      SUITE_PETSC_CHECK(VecScatterBegin(p.scatter, p.owner_side, p.rhs, INSERT_VALUES, SCATTER_FORWARD));
      SUITE_PETSC_CHECK(VecScatterEnd(p.scatter, p.owner_side, p.rhs, INSERT_VALUES, SCATTER_FORWARD));
    }
    KSP ksp = p.ksp;
    SUITE_PETSC_CHECK(KSPSolve(ksp, p.rhs, p.solution));
    KSPConvergedReason reason;
    PetscInt iterations = 0;
    PetscReal residual = 0;
    SUITE_PETSC_CHECK(KSPGetConvergedReason(ksp, &reason));
    SUITE_PETSC_CHECK(KSPGetIterationNumber(ksp, &iterations));
    SUITE_PETSC_CHECK(KSPGetResidualNorm(ksp, &residual));
    if (reason < 0)
      throw LibraryError(fmt::format(
          "the consistent drag solve (options prefix '{}') diverged for velocity component {}: {} after {} "
          "iterations, residual norm {:.3e}; the -{}ksp_* and -{}pc_* options choose the solver",
          prefix_, d, KSPConvergedReasons[reason], iterations, static_cast<double>(residual), prefix_, prefix_));
    if (iterations >= stats.iterations) {
      stats.iterations = static_cast<int>(iterations);
      stats.reason = static_cast<int>(reason);
      stats.reason_name = KSPConvergedReasons[reason];
    }
    stats.residual_norm = std::max(stats.residual_norm, static_cast<double>(residual));
    if (!layouts.same) {
      SUITE_PETSC_CHECK(VecScatterBegin(p.scatter, p.solution, p.owner_side, INSERT_VALUES, SCATTER_REVERSE));
      SUITE_PETSC_CHECK(VecScatterEnd(p.scatter, p.solution, p.owner_side, INSERT_VALUES, SCATTER_REVERSE));
    }
    ::Vec solved = layouts.same ? p.solution : p.owner_side;
    const PetscScalar* x = nullptr;
    SUITE_PETSC_CHECK(VecGetArrayRead(solved, &x));
    for (std::size_t k = 0; k < owned_slots.size(); ++k) {
      const auto slot = static_cast<std::size_t>(owned_slots[k]);
      soil_nodes.velocity[slot][d] = x[2 * k];
      water_nodes.velocity[slot][d] = x[2 * k + 1];
    }
    SUITE_PETSC_CHECK(VecRestoreArrayRead(solved, &x));
  }
  stats.krylov_s = seconds_since(krylov_start);
  return stats;
}

template class ConsistentDrag<2>;
template class ConsistentDrag<3>;
template NodeNumbering NodeNumbering::own_all<2>(const mpi::Comm&, const NodeFields<2>&, const NodeFields<2>&);
template NodeNumbering NodeNumbering::own_all<3>(const mpi::Comm&, const NodeFields<3>&, const NodeFields<3>&);
template NodeNumbering NodeNumbering::own_blocks<2>(const mpi::Comm&, const NodeFields<2>&, const NodeFields<2>&,
                                                    const std::vector<char>&);
template NodeNumbering NodeNumbering::own_blocks<3>(const mpi::Comm&, const NodeFields<3>&, const NodeFields<3>&,
                                                    const std::vector<char>&);

}  // namespace suite::mpm2grid
