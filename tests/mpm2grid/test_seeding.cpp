// Seeding over several ranks (scenes/scene.hpp, seed_particles with a communicator), on 1 and 2
// ranks: each rank seeds a band of the lattice, and together the ranks hold exactly the particles
// one rank seeds alone, each with the same id and state, bit for bit:
//   - every particle of a rank equals the one-rank particle with its id (position, velocity,
//     mass, volume, J, load);
//   - a rank's ids are consecutive and start where the lower ranks' end (exclusive prefix sum
//     of the counts), and the counts add up to the one-rank count: the ranks share out the ids
//     without a gap or a repeat;
//   - no rank holds more than its share of the particles plus one layer of the lattice;
//   - every rank numbers on after the whole scene (next_id).
// Scenes: Table 3.4 example 2 (a trapezoid dam, 2D), the Terzaghi column (saturated soil with
// pore water and a surcharge on its top row, the mixture's partial volumes) and the 3D
// decomposition scene (a water column and a soil block).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/mpm2grid/model/simulation.hpp"
#include "solvers/mpm2grid/scenes/scene.hpp"

namespace suite::mpm2grid {
namespace {

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// The largest number of particles of both species in one layer of the lattice across its last
// axis (the bands' granularity), from the one-rank particles.
template <int Dim>
long long largest_layer(const Simulation<Dim>& one, double lo, double spacing) {
  std::vector<long long> per_layer;
  for (const auto* P : {&one.water(), &one.soil()})
    for (const auto& x : P->x) {
      const auto k = static_cast<std::size_t>((x[Dim - 1] - lo) / spacing);
      if (per_layer.size() <= k) per_layer.resize(k + 1, 0);
      ++per_layer[k];
    }
  return per_layer.empty() ? 0 : *std::max_element(per_layer.begin(), per_layer.end());
}

template <int Dim>
void check_bands(const std::string& file, const std::vector<std::string>& overrides) {
  const mpi::Comm world(MPI_COMM_WORLD);
  auto sc = read_scene<Dim>(config::Config::from_file(std::string(SUITE_SOURCE_DIR) + "/" + file, overrides));
  sc.simulation.drag = DragScheme::lumped;  // the seeding does not depend on it
  Simulation<Dim> one(sc.simulation);
  seed_particles(sc, one);
  Simulation<Dim> band(sc.simulation, world);
  seed_particles(sc, band, &world);

  const double spacing = sc.simulation.h / sc.particles_per_cell;
  long long held = 0, total = 0;
  for (int species = 0; species < 2; ++species) {
    const auto& A = species == 0 ? one.water() : one.soil();
    const auto& B = species == 0 ? band.water() : band.soil();
    const auto count = static_cast<long long>(B.size());
    held += count;
    total += static_cast<long long>(A.size());
    EXPECT_EQ(world.sum(count), static_cast<long long>(A.size())) << file << ", species " << species;
    EXPECT_EQ(B.next_id, A.next_id) << file << ": numbering goes on after the whole scene";
    const long long start = world.exclusive_prefix_sum(count);
    long long mismatches = 0;
    for (std::size_t p = 0; p < B.size(); ++p) {
      if (B.id[p] != start + static_cast<long long>(p)) {
        ++mismatches;
        continue;
      }
      const auto q = static_cast<std::size_t>(B.id[p]);
      const bool same = same_bits(B.x[p], A.x[q]) && same_bits(B.v[p], A.v[q]) && same_bits(B.mass[p], A.mass[q]) &&
                        same_bits(B.volume0[p], A.volume0[q]) && same_bits(B.J[p], A.J[q]) &&
                        same_bits(B.load[p], A.load[q]) && same_bits(B.F[p], A.F[q]);
      mismatches += !same;
    }
    EXPECT_EQ(world.sum(mismatches), 0) << file << ", species " << species;
  }
  const long long share = (total + world.size() - 1) / world.size();
  const long long layer = largest_layer(one, sc.simulation.walls.lo[Dim - 1], spacing);
  const long long most = world.max(held);
  EXPECT_LE(most, share + layer) << file << ": share " << share << ", largest layer " << layer;
  if (world.is_root())
    std::printf("%s: %lld particles, at most %lld on one of %d ranks (share %lld, largest layer %lld)\n", file.c_str(),
                total, most, world.size(), share, layer);
}

TEST(SeedingOverRanks, BandsHoldTheOneRankParticles2D) {
  check_bands<2>("solvers/mpm2grid/scenes/table_3_4_example2.yaml", {"grid.spacing=0.25 m"});
  check_bands<2>("solvers/mpm2grid/scenes/terzaghi.yaml", {"grid.spacing=0.0625 m"});
}

TEST(SeedingOverRanks, BandsHoldTheOneRankParticles3D) {
  check_bands<3>("tests/mpm2grid/two_species_3d.yaml", {});
}

}  // namespace
}  // namespace suite::mpm2grid
