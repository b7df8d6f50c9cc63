#pragma once
// One species' material points as a structure of arrays (docs/methods/mpm2grid.md). Units: metres,
// seconds, kilograms; in 2D masses and volumes are per metre of thickness (kg/m, m^2).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "solvers/mpm2grid/kernels/bspline.hpp"

namespace suite::mpm2grid {

// A soil particle's eroded depth that marks it detached from the bed (erosion/bed_shear.hpp).
inline bool is_suspended(double eroded) { return eroded == std::numeric_limits<double>::infinity(); }

// Some particles of a species: those p with (*flags)[p] == value; all of them without flags (the
// free and the pore water, Simulation's free_water_field).
struct ParticleSubset {
  const std::vector<char>* flags = nullptr;
  char value = 1;
  bool has(std::size_t p) const { return !flags || (*flags)[p] == value; }
};

// Particles begin .. end - 1 of a species: a thread's share of a sweep (transfer/sweep_schedule.hpp).
struct ParticleRun {
  std::size_t begin = 0, end = 0;
};

// Takes out values[indices] (ascending, each below the size), each place filled by the last value
// that stays: values .. a b c with b and c taken out become .. a, and a taken out from a b c d
// leaves d b c.
template <class T>
void remove_at(const std::vector<std::size_t>& indices, std::vector<T>& values) {
  if (!indices.empty() && indices.back() >= values.size())
    throw std::logic_error("remove_at: an index past the end of the values");
  std::size_t end = values.size(), back = indices.size();
  for (std::size_t i = 0; i < indices.size(); ++i) {
    while (back > i && indices[back - 1] + 1 == end) --end, --back;  // the last values go
    if (indices[i] >= end) break;
    values[indices[i]] = values[--end];
  }
  values.resize(end);
}

template <int Dim>
struct Particles {
  std::vector<Vec<Dim>> x;         // position, m
  std::vector<Vec<Dim>> v;         // velocity, m/s
  std::vector<Mat<Dim>> C;         // APIC affine velocity, 1/s
  std::vector<double> mass;        // kg
  std::vector<double> volume0;     // initial volume V_p^0, m^3
  std::vector<Mat<Dim>> F;         // soil: elastic deformation gradient F_E (identity for water)
  std::vector<double> J;           // water: volume ratio J = V / V^0 (1 for soil)
  std::vector<double> log_jp;      // soil: Drucker-Prager volume correction, log of a volume ratio
  std::vector<double> saturation;  // soil: water fraction seen from the water grid, [0, 1]
  std::vector<Vec<Dim>> load;      // soil: external force at full load, N (a surcharge on the
                                   // particles of a region's upper surface; zero elsewhere)
  std::vector<double> eroded;      // soil: depth the bed shear has eroded off the particle, m;
                                   // infinity once detached: suspended (erosion/bed_shear.hpp)
  std::vector<std::int64_t> id;    // the particle's number, unique within its species over the
                                   // run and kept wherever it goes (ParaView tracks particles by it)
  std::int64_t next_id = 0;        // the number add() gives next (seeding numbers the lattice
                                   // as one rank would, over any ranks; rank 0 emits the inlet's)

  std::size_t size() const { return x.size(); }

  // Calls f(values) on each per-particle array (to reorder the particles, f applies one
  // permutation to each).
  template <class Visit>
  void for_each_array(Visit&& f) {
    f(x), f(v), f(C), f(mass), f(volume0), f(F), f(J), f(log_jp), f(saturation), f(load), f(eroded), f(id);
  }

  // Room for n particles in every array: adding up to n reallocates none.
  void reserve(std::size_t n) {
    for_each_array([n](auto& values) { values.reserve(n); });
  }

  void add(const Vec<Dim>& position, const Vec<Dim>& velocity, double m, double volume) {
    x.push_back(position);
    v.push_back(velocity);
    C.push_back(Mat<Dim>::Zero());
    mass.push_back(m);
    volume0.push_back(volume);
    F.push_back(Mat<Dim>::Identity());
    J.push_back(1.0);
    log_jp.push_back(0.0);
    saturation.push_back(0.0);
    load.push_back(Vec<Dim>::Zero());
    eroded.push_back(0.0);
    id.push_back(next_id++);
  }

  // Takes out the particles at `indices` (ascending), each place filled by the last particle that
  // stays (remove_at), and the same entries of the caller's arrays `along` (each as long as the
  // particles). A handful of particles a step leave through an outlet or to another rank, anywhere
  // in the arrays: filling their places moves as many, where closing the gaps in order moved
  // every particle behind the first one. The particles' order changes there (group_order
  // mends it when it pays).
  template <class... Along>
  void remove(const std::vector<std::size_t>& indices, std::vector<Along>&... along) {
    if (((along.size() != size()) || ...))
      throw std::logic_error("Particles::remove: the caller's arrays need an entry for every particle");
    for_each_array([&](auto& values) { remove_at(indices, values); });
    (remove_at(indices, along), ...);
  }

  // A particle's whole state as kPacked doubles (for moving it to another rank), and back (the id
  // as a double: exact below 2^53).
  static constexpr int kPacked = 3 * Dim + 2 * Dim * Dim + 7;
  void pack(std::size_t p, std::vector<double>& out) const {
    const auto put = [&](const double* a, int n) { out.insert(out.end(), a, a + n); };
    put(x[p].data(), Dim), put(v[p].data(), Dim), put(C[p].data(), Dim * Dim);
    out.insert(out.end(), {mass[p], volume0[p]});
    put(F[p].data(), Dim * Dim);
    out.insert(out.end(), {J[p], log_jp[p], saturation[p]});
    put(load[p].data(), Dim);
    out.insert(out.end(), {eroded[p], static_cast<double>(id[p])});
  }
  // Appends the particle packed at `in` (kPacked doubles).
  void add_packed(const double* in) {
    const auto take = [&](auto& m, int n) {
      std::copy(in, in + n, m.data());
      in += n;
    };
    Vec<Dim> xp, vp;
    Mat<Dim> Cp, Fp;
    take(xp, Dim), take(vp, Dim), take(Cp, Dim * Dim);
    x.push_back(xp), v.push_back(vp), C.push_back(Cp);
    mass.push_back(in[0]), volume0.push_back(in[1]);
    in += 2;
    take(Fp, Dim * Dim);
    F.push_back(Fp);
    J.push_back(in[0]), log_jp.push_back(in[1]), saturation.push_back(in[2]);
    in += 3;
    Vec<Dim> lp;
    take(lp, Dim);
    load.push_back(lp);
    eroded.push_back(in[0]);
    id.push_back(static_cast<std::int64_t>(in[1]));
  }

  double total_mass() const {
    double m = 0;
    for (double mp : mass) m += mp;
    return m;
  }
  Vec<Dim> momentum() const {
    Vec<Dim> p = Vec<Dim>::Zero();
    for (std::size_t i = 0; i < size(); ++i) p += mass[i] * v[i];
    return p;
  }
};

}  // namespace suite::mpm2grid
