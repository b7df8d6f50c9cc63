#include "solvers/mpm2grid/io/checkpoint_state.hpp"

#include <limits>
#include <span>
#include <vector>

#include "core/errors.hpp"

namespace suite::mpm2grid {
namespace {

// Eigen's fixed-size vectors and matrices are plain arrays of doubles, so an array of them is
// stored as one flat array of doubles.
template <class T>
std::span<const double> flat(const std::vector<T>& v) {
  static_assert(sizeof(T) % sizeof(double) == 0);
  return {reinterpret_cast<const double*>(v.data()), v.size() * (sizeof(T) / sizeof(double))};
}

template <class T>
void unflatten(const std::vector<double>& data, std::vector<T>& out, const std::string& name) {
  constexpr std::size_t per = sizeof(T) / sizeof(double);
  if (data.size() % per != 0)
    throw LibraryError("checkpoint array '" + name + "' does not hold whole " + std::to_string(per) + "-vectors");
  out.resize(data.size() / per);
  std::copy(data.begin(), data.end(), reinterpret_cast<double*>(out.data()));
}

template <int Dim>
void write_species(checkpoint::Writer& w, const std::string& s, const Particles<Dim>& P) {
  w.write<double>(s + "/x", flat(P.x));
  w.write<double>(s + "/v", flat(P.v));
  w.write<double>(s + "/C", flat(P.C));
  w.write<double>(s + "/mass", P.mass);
  w.write<double>(s + "/volume0", P.volume0);
  w.write<double>(s + "/F", flat(P.F));
  w.write<double>(s + "/J", P.J);
  w.write<double>(s + "/log_jp", P.log_jp);
  w.write<double>(s + "/saturation", P.saturation);
  w.write<double>(s + "/load", flat(P.load));
  w.write<double>(s + "/eroded", P.eroded);
  std::vector<long long> id(P.id.begin(), P.id.end());
  w.write<long long>(s + "/id", id);
}

template <int Dim>
void read_species(checkpoint::Reader& r, const std::string& s, Particles<Dim>& P) {
  unflatten(r.read<double>(s + "/x"), P.x, s + "/x");
  unflatten(r.read<double>(s + "/v"), P.v, s + "/v");
  unflatten(r.read<double>(s + "/C"), P.C, s + "/C");
  P.mass = r.read<double>(s + "/mass");
  P.volume0 = r.read<double>(s + "/volume0");
  unflatten(r.read<double>(s + "/F"), P.F, s + "/F");
  P.J = r.read<double>(s + "/J");
  P.log_jp = r.read<double>(s + "/log_jp");
  P.saturation = r.read<double>(s + "/saturation");
  unflatten(r.read<double>(s + "/load"), P.load, s + "/load");
  P.eroded = r.read<double>(s + "/eroded");
  const auto id = r.read<long long>(s + "/id");
  P.id.assign(id.begin(), id.end());
  const std::size_t n = P.x.size();
  for (std::size_t m : {P.v.size(), P.C.size(), P.mass.size(), P.volume0.size(), P.F.size(), P.J.size(),
                        P.log_jp.size(), P.saturation.size(), P.load.size(), P.eroded.size(), P.id.size()})
    if (m != n) throw LibraryError("checkpoint species '" + s + "' has arrays of different lengths");
}

}  // namespace

// The run's scalars, in this order, then the outflow momentum (Dim values), then the implicit
// forces' dt cap (absent from the checkpoints of builds before it: no cap), then the outflow's
// share of the excess-stress erosion (absent before it: none).
constexpr std::size_t kScalars = 14;

template <int Dim>
void write_state(checkpoint::Writer& w, const Simulation<Dim>& sim, const RunProgress& progress) {
  write_species(w, "water", sim.water());
  write_species(w, "soil", sim.soil());
  const auto& o = sim.outflow();
  const auto& q = progress.outlet;
  const InletState inlet = sim.inlet() ? sim.inlet()->state() : InletState{};
  std::vector<double> scalars{sim.time(),           o.water_mass,
                              o.soil_mass,          progress.next_sample,
                              progress.next_output, progress.smallest_dt,
                              q.last_time,          q.last_water_mass,
                              q.last_soil_mass,     q.peak_water_discharge,
                              q.peak_time,          progress.initial_soil_volume,
                              inlet.length,         inlet.mass};
  for (int d = 0; d < Dim; ++d) scalars.push_back(o.momentum[d]);
  scalars.push_back(progress.dt_cap);
  scalars.push_back(o.shear_eroded_volume);
  scalars.push_back(o.law_eroded_volume);
  w.write<double>("run/scalars", scalars);
  std::vector<long long> counters{sim.steps(), progress.files, inlet.layers, sim.water().next_id, sim.soil().next_id};
  w.write<long long>("run/counters", counters);
  // Limiter names and counts as "name=count" lines.
  std::string limiters;
  for (const auto& [name, n] : progress.limiters) limiters += name + "=" + std::to_string(n) + "\n";
  w.write_bytes("run/limiters", std::as_bytes(std::span(limiters.data(), limiters.size())));
  // The owner table over several ranks (each rank its blocks; empty on one rank).
  const auto* dd = sim.decomposition();
  w.write<long long>("decomposition/owned_blocks", dd ? dd->owned_keys() : std::vector<long long>{});
}

template <int Dim>
void read_state(checkpoint::Reader& r, Simulation<Dim>& sim, RunProgress& progress) {
  read_species(r, "water", sim.water());
  read_species(r, "soil", sim.soil());
  const auto scalars = r.read<double>("run/scalars");
  const auto counters = r.read<long long>("run/counters");
  if (scalars.size() < kScalars + Dim || scalars.size() > kScalars + Dim + 3 || counters.size() != 5)
    throw LibraryError("checkpoint run record has another layout than this build's");
  Outflow<Dim> o;
  o.water_mass = scalars[1], o.soil_mass = scalars[2];
  o.shear_eroded_volume = scalars.size() > kScalars + Dim + 1 ? scalars[kScalars + Dim + 1] : 0.0;
  o.law_eroded_volume = scalars.size() > kScalars + Dim + 2 ? scalars[kScalars + Dim + 2] : 0.0;  // older: 0
  for (int d = 0; d < Dim; ++d) o.momentum[d] = scalars[kScalars + d];
  const InletState inlet{scalars[12], counters[2], scalars[13]};
  sim.restore(scalars[0], counters[0], o, inlet);
  progress.next_sample = scalars[3], progress.next_output = scalars[4], progress.smallest_dt = scalars[5];
  progress.outlet = {scalars[6], scalars[7], scalars[8], scalars[9], scalars[10]};
  progress.initial_soil_volume = scalars[11];
  progress.dt_cap = scalars.size() > kScalars + Dim ? scalars[kScalars + Dim] : std::numeric_limits<double>::infinity();
  progress.files = counters[1];
  sim.water().next_id = counters[3], sim.soil().next_id = counters[4];
  progress.limiters.clear();
  const auto bytes = r.read_bytes("run/limiters");
  const std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  for (std::size_t start = 0, end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    const std::string line = text.substr(start, end - start);
    const auto eq = line.rfind('=');
    progress.limiters[line.substr(0, eq)] = std::stoll(line.substr(eq + 1));
  }
  const auto owned_blocks = r.read<long long>("decomposition/owned_blocks");
  if (auto* dd = sim.decomposition()) dd->restore(owned_blocks);
}

template void write_state<2>(checkpoint::Writer&, const Simulation<2>&, const RunProgress&);
template void write_state<3>(checkpoint::Writer&, const Simulation<3>&, const RunProgress&);
template void read_state<2>(checkpoint::Reader&, Simulation<2>&, RunProgress&);
template void read_state<3>(checkpoint::Reader&, Simulation<3>&, RunProgress&);

}  // namespace suite::mpm2grid
