#pragma once
// APIC transfers with cubic B-splines (Jiang et al. 2015; docs/methods/mpm2grid.md, steps 1, 2 and 5),
// one species at a time:
//   P2G  m_i = sum_p w_ip m_p,   (m v)_i = sum_p w_ip m_p (v_p + C_p (x_i - x_p)),
//        f_i = -sum_p V_p^0 tau_p grad w_ip   (tau_p the Kirchhoff stress: V^0 P F^T = V^0 tau)
//              + sum_p w_ip g_p               (g_p a body force on the particle: m_p g, and the
//                                              soil's buoyancy),
//        d_i = sum_p (c_E V)_p w_ip           (drag coefficients, soil only, when given);
//   G2P  v_p = sum_i w_ip v_i,   C_p = sum_i w_ip v_i (x_i - x_p)^T D^-1,  D^-1 = 3 / h^2,
//        grad v_p = sum_i v_i (grad w_ip)^T.
// P2G conserves mass, linear and angular momentum exactly (the weights are a partition of unity
// and reproduce linear functions); G2P then P2G loses no angular momentum either. The walls'
// mirror condition (boundary/wall_fold.hpp), where a scene has walls, keeps the mass and the
// momentum along each wall and reverses the part across it that particles spread beyond it.
// Both go through a NodeTile per particle group (grid/node_tile.hpp) with the row kernels of
// transfer/stencil_rows.hpp; they give the same sums for particles in any order, and work
// fastest in group order (transfer/particle_order.hpp).
#include <array>
#include <memory>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "solvers/mpm2grid/boundary/wall_fold.hpp"
#include "solvers/mpm2grid/grid/block_grid.hpp"
#include "solvers/mpm2grid/grid/node_tile.hpp"
#include "solvers/mpm2grid/particles/particles.hpp"
#include "solvers/mpm2grid/transfer/stencil_rows.hpp"

namespace suite::mpm2grid {

namespace detail {

// For particles begin .. end - 1 in order: reach(b) for each block b their stencils reach, once per
// group met (its return value, >= 0, stands for the block until the group changes), and each(p,
// first) with `first` what reach() returned for the particle's group block.
template <int Dim, class Reach, class Each>
void sweep_reached_blocks(const Particles<Dim>& particles, std::size_t begin, std::size_t end, double h, Reach&& reach,
                          Each&& each) {
  using Grid = BlockGrid<Dim>;
  // The blocks g + {0, 1}^Dim around the current group g (offset bit d: the next block along axis
  // d; -1: not reached by this sweep yet). The particles come mostly in group order, so a block is
  // reached about once per group, not once per particle, and in the same order as touching each
  // particle's stencil would.
  std::array<int, Grid::kStencilBlocks> around{};
  typename Grid::Key group = 0;
  Index<Dim> previous{};
  int first = -1;  // for the current particle's group block
  for (std::size_t p = begin; p < end; ++p) {
    const Index<Dim> base = stencil_base(particles.x[p], h);
    int moved = p == begin;  // compared per component (not as arrays: a store-forwarding stall)
    for (int d = 0; d < Dim; ++d) moved |= base[d] ^ previous[d];
    if (moved) {
      const Index<Dim> g = Grid::block_holding(base);
      if (p == begin || Grid::key(g) != group) {
        group = Grid::key(g);
        around.fill(-1);
      }
      // The stencil reaches the next block along the axes where its last node base + 3 lies
      // there; the blocks g + corner for the corners within those axes, in ascending corner
      // order (as BlockGrid::touch()).
      int reach_axes = 0;
      for (int d = 0; d < Dim; ++d) reach_axes |= (base[d] + 3 - g[d] * Grid::kSide >= Grid::kSide) << d;
      for (int corner = 0; corner < Grid::kStencilBlocks; ++corner) {
        if ((corner & ~reach_axes) != 0 || around[static_cast<std::size_t>(corner)] >= 0) continue;
        Index<Dim> b = g;
        for (int d = 0; d < Dim; ++d) b[d] += (corner >> d) & 1;
        around[static_cast<std::size_t>(corner)] = reach(b);
      }
      first = around[0];
      previous = base;
    }
    each(p, first);
  }
}

}  // namespace detail

// Activates the grid blocks the particles' stencils touch, a block's hash lookup about once per
// group. With `groups`, also gives each particle's group (grid/node_tile.hpp) as the index of its
// block (one entry per particle).
template <int Dim>
void touch_blocks(const Particles<Dim>& particles, BlockGrid<Dim>& grid, std::vector<int>* groups = nullptr) {
  if (groups) groups->resize(particles.size());
  detail::sweep_reached_blocks(
      particles, 0, particles.size(), grid.spacing(), [&](const Index<Dim>& b) { return grid.activate(b); },
      [&](std::size_t p, int first) {
        if (groups) (*groups)[p] = first;
      });
}

// touch_blocks over threads, in three passes that activate the same blocks in the same order (the
// order in which a block's first stencil comes): each thread lists the blocks the stencils of its
// share of the particles reach (blocks_reached, each group's once), the lists are activated one
// after the other in the particles' order, and each thread then finds its particles' groups
// (find_groups).
template <int Dim>
void blocks_reached(const Particles<Dim>& particles, ParticleRun run, double h, std::vector<Index<Dim>>& out) {
  out.clear();
  detail::sweep_reached_blocks(
      particles, run.begin, run.end, h,
      [&](const Index<Dim>& b) {
        out.push_back(b);
        return 0;  // listed
      },
      [](std::size_t, int) {});
}

template <int Dim>
void find_groups(const Particles<Dim>& particles, const BlockGrid<Dim>& grid, ParticleRun run,
                 std::vector<int>& groups) {
  using Grid = BlockGrid<Dim>;
  typename Grid::Key group = 0;
  int index = -1;
  for (std::size_t p = run.begin; p < run.end; ++p) {
    const Index<Dim> g = Grid::block_holding(stencil_base(particles.x[p], grid.spacing()));
    if (p == run.begin || Grid::key(g) != group) group = Grid::key(g), index = grid.find_block(g);
    groups[p] = index;
  }
}

// What P2G spreads besides the particles' mass and APIC momentum (each null when not used).
template <int Dim>
struct P2GSources {
  // The internal force -V0 tau_p grad w_ip, from either a Kirchhoff stress tau per particle (Pa)
  const std::vector<Mat<Dim>>* tau = nullptr;
  // or a pressure p per particle (Pa): the water's tau = -J p I. Then w_ip m_p p_p is also added
  // to nodes.pressure (the buoyancy's node pressures).
  const std::vector<double>* pressure = nullptr;
  // false: the pressure's force is left out, its node sums still spread (the implicit forces,
  // model/implicit_forces.cpp, add the force at the step's end).
  bool pressure_force = true;
  // c_E V per particle (kg/s): w_ip c_E V into nodes.drag (not with `pressure`).
  const std::vector<double>* drag = nullptr;
  // Buoyancy: the body force -V_s grad p on each particle, spread with w_ip, V_s per particle
  // (m^3) and grad p = sum_i p_i grad w_ip from node pressures p_i per slot (Pa).
  const std::vector<double>* solid_volume = nullptr;
  const std::vector<double>* node_pressure = nullptr;
  // > 0: the forces times fold_dt go into nodes.momentum (m v + dt f, what the lumped and
  // consistent drag solves read; nodes.force is left alone). 0: into nodes.force.
  double fold_dt = 0;
  // The walls' mirror condition (boundary/wall_fold.hpp): each tile folded before it is added to
  // the grid, the node pressures read mirrored.
  const WallFold<Dim>* walls = nullptr;
  // Gravity (m/s^2): the body force m_p g spread with w_ip like the others, so that the walls'
  // fold treats it as it treats them.
  Vec<Dim> gravity = Vec<Dim>::Zero();
  // With a FLIP share: the particles' mass and APIC momentum alone (no forces) are also added to
  // before->mass and before->momentum (reset by the caller) in the same sweep. With fold_dt > 0
  // the forces are then kept apart in the tile and folded into nodes.momentum as it is added.
  NodeFields<Dim>* before = nullptr;
  // Only these particles (the free or the pore water); all by default.
  ParticleSubset subset = {};
  // Only the particles of these runs (a thread's part: transfer/sweep_schedule.hpp); all if empty.
  std::span<const ParticleRun> runs = {};
};

namespace detail {

template <StressForm Form, bool Fold, int Dim>
void particles_to_grid(const Particles<Dim>& P, const P2GSources<Dim>& in, const BlockGrid<Dim>& grid,
                       NodeFields<Dim>& nodes) {
  // Tile fields: mass, momentum, [force,] the drag or pressure sums, the node pressures read.
  constexpr int kExtra = Fold ? 1 + Dim : 1 + 2 * Dim;
  constexpr int kRead = kExtra + 1;
  using Tile = NodeTile<Dim, kRead + 1>;
  auto tile = std::make_unique<Tile>();
  const bool forced = !Fold && (Form != StressForm::none || in.node_pressure || !in.gravity.isZero(0.0));
  const bool extra = in.drag || in.pressure;
  std::vector<double>& extra_field = in.drag ? nodes.drag : nodes.pressure;
  // What each tile field holds, for the walls' fold: the sums it adds, and the pressures it reads.
  constexpr auto fields = [] {
    std::array<TileField, kRead + 1> f{};
    for (int a = 0; a < Dim; ++a) {
      f[static_cast<std::size_t>(1 + a)] = {TileField::component, a};
      if constexpr (!Fold) f[static_cast<std::size_t>(1 + Dim + a)] = {TileField::component, a};
    }
    f[kRead] = {TileField::untouched};
    return f;
  }();
  constexpr auto read = [] {
    std::array<TileField, kRead + 1> f{};
    for (auto& field : f) field = {TileField::untouched};
    f[kRead] = {TileField::scalar};
    return f;
  }();
  const auto enter = [&] {
    if (!in.node_pressure) return tile->zero();
    tile->gather(kRead, *in.node_pressure);
    if (in.walls) in.walls->mirror(*tile, read);
  };
  // Only with `before` does a folding P2G come here (Fold false): its forces fold as they are added.
  const double fold_at_leave = Fold ? 0.0 : in.fold_dt;
  const auto leave = [&] {
    if (in.walls) in.walls->fold(*tile, fields);
    tile->for_each_node([&](int t, long slot) {
      const auto i = static_cast<std::size_t>(slot);
      nodes.mass[i] += tile->field(0)[t];
      for (int a = 0; a < Dim; ++a) nodes.momentum[i][a] += tile->field(1 + a)[t];
      if (fold_at_leave > 0)
        for (int a = 0; a < Dim; ++a) nodes.momentum[i][a] += fold_at_leave * tile->field(1 + Dim + a)[t];
      else if (forced)
        for (int a = 0; a < Dim; ++a) nodes.force[i][a] += tile->field(1 + Dim + a)[t];
      if (extra) extra_field[i] += tile->field(kExtra)[t];
      if (in.before) {
        in.before->mass[i] += tile->field(0)[t];
        for (int a = 0; a < Dim; ++a) in.before->momentum[i][a] += tile->field(1 + a)[t];
      }
    });
  };
  Mat<Dim> S = Mat<Dim>::Zero();
  sweep_groups(
      P.x, grid, *tile, enter, leave,
      [&](std::size_t p, const StencilRows<Dim>& s, int first) {
        if constexpr (Form == StressForm::full) S = P.volume0[p] * (*in.tau)[p];
        if constexpr (Form == StressForm::isotropic) S(0, 0) = -P.volume0[p] * P.J[p] * (*in.pressure)[p];
        Vec<Dim> g = P.mass[p] * in.gravity;
        if (in.node_pressure)
          g -= (*in.solid_volume)[p] * sample_field<false, kAllAxes>(*tile, kRead, s, first).gradient;
        const double e = !extra ? 0.0 : in.drag ? (*in.drag)[p] : P.mass[p] * (*in.pressure)[p];
        scatter_apic<Form, Fold>(*tile, s, first, P.mass[p], P.v[p], P.C[p], S, g, in.fold_dt, extra ? kExtra : -1, e);
      },
      in.subset, in.runs);
}

template <bool Fold, int Dim>
void particles_to_grid(const Particles<Dim>& P, const P2GSources<Dim>& in, const BlockGrid<Dim>& grid,
                       NodeFields<Dim>& nodes) {
  if (in.tau)
    particles_to_grid<StressForm::full, Fold>(P, in, grid, nodes);
  else if (in.pressure && in.pressure_force)
    particles_to_grid<StressForm::isotropic, Fold>(P, in, grid, nodes);
  else
    particles_to_grid<StressForm::none, Fold>(P, in, grid, nodes);
}

}  // namespace detail

// Adds one species' particles to its node fields (reset to the grid's size by the caller): mass,
// APIC momentum and what `in` names. The particles' stencils must lie in active blocks
// (touch_blocks); with buoyancy, the node pressures must be known on every active node.
template <int Dim>
void particles_to_grid(const Particles<Dim>& P, const P2GSources<Dim>& in, const BlockGrid<Dim>& grid,
                       NodeFields<Dim>& nodes) {
  if ((in.tau && in.pressure) || (in.drag && in.pressure) || (!in.solid_volume != !in.node_pressure))
    throw std::invalid_argument(
        "particles_to_grid: give tau or pressure (not both), drag or pressure (not both), and solid_volume "
        "together with node_pressure");
  if (in.fold_dt > 0 && !in.before)
    detail::particles_to_grid<true>(P, in, grid, nodes);
  else
    detail::particles_to_grid<false>(P, in, grid, nodes);
}

// What G2P samples of the velocity's gradient besides v_p and C_p.
enum class VelocityGradient {
  full,        // grad v_p
  divergence,  // div v_p alone: one gradient component per velocity component (3 of 9 in 3D)
  none,
};

// A FLIP share in G2P (Simulation's water.flip and soil.flip): with the node velocities
// before the step's forces v_i^0 (complete on the nodes the particles reach) and the share a,
//   v_p <- a (v_p + sum_i w_ip v_i - sum_i w_ip v_i^0) + (1 - a) sum_i w_ip v_i,
// i.e. the particle keeps its own velocity and takes the grid's change, blended with APIC's
// velocity; C_p and grad v_p stay APIC's. No `before`: APIC alone.
template <int Dim>
struct FlipBlend {
  const NodeFields<Dim>* before = nullptr;
  double share = 0;
};

namespace detail {

// No gradient for field a (a pack of sample_fields' Axes, one per field).
constexpr Axes no_gradient(int) {
  return kNoAxes;
}

// grid_to_particles_each with the FLIP blend (Blend) or without.
template <VelocityGradient Gradient, bool Blend, int Dim, class Each>
void grid_to_particles(Particles<Dim>& P, const BlockGrid<Dim>& grid, const NodeFields<Dim>& nodes,
                       const std::vector<double>* field, std::vector<double>* at_particles, const WallFold<Dim>* walls,
                       Each&& each, const FlipBlend<Dim>& flip, const ParticleSubset& subset,
                       std::span<const ParticleRun> runs) {
  // Velocity, the sampled field, and with the blend the velocity before the forces.
  constexpr int kFields = Blend ? 2 * Dim + 1 : Dim + 1;
  using Tile = NodeTile<Dim, kFields>;
  auto tile = std::make_unique<Tile>();
  const double inverse_d = apic_inverse_d(grid.spacing());
  if (at_particles && runs.empty()) at_particles->resize(P.size());  // a part's caller sized it
  constexpr auto fields = [] {
    std::array<TileField, kFields> f{};
    for (int a = 0; a < Dim; ++a) f[static_cast<std::size_t>(a)] = {TileField::component, a};
    if constexpr (Blend)
      for (int a = 0; a < Dim; ++a) f[static_cast<std::size_t>(Dim + 1 + a)] = {TileField::component, a};
    return f;
  }();
  const auto enter = [&] {
    tile->zero();
    tile->for_each_node([&](int t, long slot) {
      const auto i = static_cast<std::size_t>(slot);
      for (int a = 0; a < Dim; ++a) tile->field(a)[t] = nodes.velocity[i][a];
      if (field) tile->field(Dim)[t] = (*field)[i];
      if constexpr (Blend)
        for (int a = 0; a < Dim; ++a) tile->field(Dim + 1 + a)[t] = flip.before->velocity[i][a];
    });
    if (walls) walls->mirror(*tile, fields);
  };
  sweep_groups(
      P.x, grid, *tile, enter, [] {},
      [&](std::size_t p, const StencilRows<Dim>& s, int first) {
        constexpr auto axes = [](int a) {
          return Gradient == VelocityGradient::full         ? kAllAxes
                 : Gradient == VelocityGradient::divergence ? only_axis(a)
                                                            : kNoAxes;
        };
        const auto velocity = [&]<int... a>(std::integer_sequence<int, a...>) {
          return sample_fields<true, axes(a)...>(*tile, 0, s, first);
        }
        (std::make_integer_sequence<int, Dim>{});
        Mat<Dim> grad_v;  // with the divergence only its diagonal (the rest 0)
        for (int a = 0; a < Dim; ++a) {
          const FieldSample<Dim>& va = velocity[static_cast<std::size_t>(a)];
          P.C[p].row(a) = inverse_d * va.moment.transpose();
          grad_v.row(a) = va.gradient.transpose();
        }
        if constexpr (Blend) {
          const auto before = [&]<int... a>(std::integer_sequence<int, a...>) {
            return sample_fields<false, no_gradient(a)...>(*tile, Dim + 1, s, first);
          }
          (std::make_integer_sequence<int, Dim>{});
          for (int a = 0; a < Dim; ++a) {
            const double apic = velocity[static_cast<std::size_t>(a)].value;
            P.v[p][a] =
                flip.share * (P.v[p][a] + apic - before[static_cast<std::size_t>(a)].value) + (1 - flip.share) * apic;
          }
        } else {
          for (int a = 0; a < Dim; ++a) P.v[p][a] = velocity[static_cast<std::size_t>(a)].value;
        }
        if (field) (*at_particles)[p] = sample_field<false, kNoAxes>(*tile, Dim, s, first).value;
        if constexpr (Gradient == VelocityGradient::full)
          each(p, grad_v);
        else if constexpr (Gradient == VelocityGradient::divergence)
          each(p, grad_v.trace());  // summed as the full gradient's trace
        else
          each(p);
      },
      subset, runs);
}

}  // namespace detail

// G2P over the particles in order: v_p and C_p, with `field` sum_i w_ip field_i into
// `at_particles` (resized; the soil's saturation from the water's node masses), then
// each(p, grad v_p) (full), each(p, div v_p) (divergence) or each(p) (none) for the caller to
// keep what it needs. With `walls`, the nodes beyond the walls are read as their mirrors
// (boundary/wall_fold.hpp); with `flip.before`, v_p is blended with FLIP (FlipBlend). Only the
// particles of `subset` are visited, and with `runs` only those of the runs (a thread's part:
// transfer/sweep_schedule.hpp; `at_particles` must then be sized already).
template <VelocityGradient Gradient, int Dim, class Each>
void grid_to_particles_each(Particles<Dim>& P, const BlockGrid<Dim>& grid, const NodeFields<Dim>& nodes,
                            const std::vector<double>* field, std::vector<double>* at_particles,
                            const std::type_identity_t<WallFold<Dim>>* walls, Each&& each,
                            const FlipBlend<Dim>& flip = {}, const ParticleSubset& subset = {},
                            std::span<const ParticleRun> runs = {}) {
  if (!field != !at_particles) throw std::invalid_argument("grid_to_particles: a field to sample needs its output");
  if (flip.before)
    detail::grid_to_particles<Gradient, true>(P, grid, nodes, field, at_particles, walls, each, flip, subset, runs);
  else
    detail::grid_to_particles<Gradient, false>(P, grid, nodes, field, at_particles, walls, each, flip, subset, runs);
}

// Interpolates the node velocities back: v_p, C_p and grad v_p (one per particle, resized), and,
// with `field`, sum_i w_ip field_i per particle into `at_particles` (resized) in the same sweep;
// with `walls`, the walls' mirror condition; with `flip.before`, the FLIP blend; with `runs`, a
// thread's part (grad_v and at_particles sized by the caller).
template <int Dim>
void grid_to_particles(Particles<Dim>& P, const BlockGrid<Dim>& grid, const NodeFields<Dim>& nodes,
                       std::vector<Mat<Dim>>& grad_v, const std::vector<double>* field = nullptr,
                       std::vector<double>* at_particles = nullptr, const WallFold<Dim>* walls = nullptr,
                       const FlipBlend<Dim>& flip = {}, std::span<const ParticleRun> runs = {}) {
  if (runs.empty()) grad_v.resize(P.size());
  grid_to_particles_each<VelocityGradient::full>(
      P, grid, nodes, field, at_particles, walls, [&](std::size_t p, const Mat<Dim>& g) { grad_v[p] = g; }, flip, {},
      runs);
}

}  // namespace suite::mpm2grid
