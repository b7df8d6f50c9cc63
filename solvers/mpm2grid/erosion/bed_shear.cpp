#include "solvers/mpm2grid/erosion/bed_shear.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace suite::mpm2grid {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2, the g a Manning n is measured under
constexpr double kNoBed = -std::numeric_limits<double>::infinity();

}  // namespace

template <int Dim>
BedShear<Dim>::BedShear(const Walls<Dim>& walls, double h, double water_density, double soil_density,
                        BedShearSettings shear, ExcessStressSettings erosion, const Vec<Dim>& gravity)
    : lo_(walls.lo),
      h_(h),
      inv_h_(1 / h),
      rho_w_(water_density),
      rho_s_(soil_density),
      floor_(walls.kind[1][0] != WallKind::open),
      shear_(shear),
      erosion_(erosion) {
  const double g = gravity.norm();
  down_ = g > 0 ? Vec<Dim>(gravity / g) : Vec<Dim>(Vec<Dim>::Zero());
  std::size_t n = 1;
  for (int d = 0; d < Dim; ++d) {
    count_[d] = d == 1 ? 1 : std::max(1L, std::lround((walls.hi[d] - walls.lo[d]) / h));
    n *= static_cast<std::size_t>(count_[d]);
  }
  columns_.resize(n);
}

template <int Dim>
std::size_t BedShear<Dim>::column_of(const Vec<Dim>& x) const {
  std::size_t c = 0, stride = 1;
  for (int d = 0; d < Dim; ++d) {
    if (d == 1) continue;
    const long i = std::clamp(static_cast<long>(std::floor((x[d] - lo_[d]) * inv_h_)), 0L, count_[d] - 1);
    c += static_cast<std::size_t>(i) * stride;
    stride *= static_cast<std::size_t>(count_[d]);
  }
  return c;
}

template <int Dim>
Vec<Dim> BedShear<Dim>::column_centre(std::size_t c) const {
  Vec<Dim> x = Vec<Dim>::Zero();
  for (int d = 0; d < Dim; ++d) {
    if (d == 1) continue;
    const auto n = static_cast<std::size_t>(count_[d]);
    x[d] = lo_[d] + (static_cast<double>(c % n) + 0.5) * h_;
    c /= n;
  }
  return x;
}

template <int Dim>
double BedShear<Dim>::side(const Particles<Dim>& soil, std::size_t p) const {
  const double v = soil.mass[p] / rho_s_;
  return Dim == 2 ? std::sqrt(v) : std::cbrt(v);
}

template <int Dim>
void BedShear<Dim>::measure(const Particles<Dim>& water, const Particles<Dim>& soil, const mpi::Comm* comm,
                            const std::vector<char>* free) {
  const std::size_t n = columns_.size();
  // The beds: the highest top of each column's bed soil. Each soil particle's column is kept for
  // erode(), which sees the particles where and in the order they are now.
  std::vector<double> top(n, kNoBed);
  soil_column_.resize(soil.size());
  for (std::size_t p = 0; p < soil.size(); ++p) {
    const std::size_t c = column_of(soil.x[p]);
    soil_column_[p] = static_cast<std::uint32_t>(c);
    if (suspended(soil, p)) continue;
    top[c] = std::max(top[c], soil.x[p][1] + 0.5 * side(soil, p));
  }
  if (comm && comm->size() > 1) comm->all_reduce(top, mpi::Comm::Reduction::max);
  for (std::size_t c = 0; c < n; ++c) {
    auto& col = columns_[c];
    col = BedColumn<Dim>{};
    const double bed = floor_ ? std::max(top[c], lo_[1]) : top[c];
    col.has_bed = bed > kNoBed;
    col.bed = col.has_bed ? bed : 0.0;
  }
  slopes();

  // The free water above each bed: volume, mass and momentum; and each column's top layer, the
  // bed particles the erosion shares the column's volume among (whole counts: exact over ranks).
  constexpr int kSums = 3 + Dim;
  sums_.assign(n * kSums, 0.0);
  for (std::size_t p = 0; p < water.size(); ++p) {
    const std::size_t c = column_of(water.x[p]);
    if (!columns_[c].has_bed || !(free ? (*free)[p] : water.x[p][1] > columns_[c].bed)) continue;
    double* s = &sums_[c * kSums];
    s[0] += water.volume0[p] * water.J[p];
    s[1] += water.mass[p];
    for (int d = 0; d < Dim; ++d) s[2 + d] += water.mass[p] * water.v[p][d];
  }
  if (erosion_.on)
    for (std::size_t p = 0; p < soil.size(); ++p)
      if (in_top_layer(soil, p)) sums_[soil_column_[p] * kSums + 2 + Dim] += 1;
  if (comm && comm->size() > 1) comm->all_reduce(sums_, mpi::Comm::Reduction::sum);

  const double area = std::pow(h_, Dim - 1);  // a column's cross-section (per metre of width in 2D)
  const double n2 = shear_.manning_n * shear_.manning_n;
  for (std::size_t c = 0; c < n; ++c) {
    auto& col = columns_[c];
    const double* s = &sums_[c * kSums];
    col.top_layer = s[2 + Dim];
    if (!col.has_bed || !(s[1] > 0)) continue;
    const double depth = s[0] / (area * col.secant);
    if (depth < 0.5 * h_) continue;  // an unresolved film: dry
    Vec<Dim> U;
    for (int d = 0; d < Dim; ++d) U[d] = s[2 + d] / s[1];
    col.depth = depth;
    col.velocity = U - U.dot(col.normal) * col.normal;
    col.shear = rho_w_ * kStandardGravity * n2 * col.velocity.squaredNorm() / std::cbrt(depth);
  }
}

// The beds' normals and secants from the neighbouring columns' beds.
template <int Dim>
void BedShear<Dim>::slopes() {
  const std::size_t n = columns_.size();
  std::size_t stride = 1;
  std::vector<Vec<Dim>> gradient(n, Vec<Dim>::Zero());
  for (int d = 0; d < Dim; ++d) {
    if (d == 1) continue;
    const auto count = static_cast<std::size_t>(count_[d]);
    for (std::size_t c = 0; c < n; ++c) {
      if (!columns_[c].has_bed) continue;
      const std::size_t i = (c / stride) % count;
      const bool left = i > 0 && columns_[c - stride].has_bed, right = i + 1 < count && columns_[c + stride].has_bed;
      const double low = left ? columns_[c - stride].bed : columns_[c].bed;
      const double high = right ? columns_[c + stride].bed : columns_[c].bed;
      const int spans = int{left} + int{right};
      if (spans > 0) gradient[c][d] = (high - low) / (spans * h_);
    }
    stride *= count_[d];
  }
  for (std::size_t c = 0; c < n; ++c) {
    Vec<Dim> normal = -gradient[c];
    normal[1] = 1;
    columns_[c].secant = normal.norm();
    columns_[c].normal = normal / columns_[c].secant;
  }
}

// A bed particle whose top lies within half its side of its column's bed (measure()'s beds).
template <int Dim>
bool BedShear<Dim>::in_top_layer(const Particles<Dim>& soil, std::size_t p) const {
  const auto& col = columns_[soil_column_[p]];
  return col.has_bed && !suspended(soil, p) && !(soil.x[p][1] + side(soil, p) < col.bed);
}

template <int Dim>
double BedShear<Dim>::erode(Particles<Dim>& soil, double dt, std::vector<std::size_t>* detached) const {
  if (!erosion_.on) return 0;
  const double area = std::pow(h_, Dim - 1);  // a column's cross-section
  double taken = 0;
  for (const auto& col : columns_)
    if (col.depth > 0 && col.top_layer > 0 && col.shear > erosion_.tau_c)
      taken += dt * erosion_.kd * (col.shear - erosion_.tau_c) * col.secant * area;
  for (std::size_t p = 0; p < soil.size(); ++p) {
    const auto& col = columns_[soil_column_[p]];
    if (!col.has_bed) continue;
    const double s = side(soil, p);
    const bool calm = !(col.depth > 0) || col.shear <= erosion_.tau_c;
    if (suspended(soil, p)) {  // deposits where it reaches a calm bed
      if (calm && soil.x[p][1] - 0.5 * s <= col.bed) soil.eroded[p] = 0;
      continue;
    }
    if (calm || !in_top_layer(soil, p)) continue;  // not exposed to a flow that erodes
    // The column's volume over its top layer, as a depth of this particle.
    const double volume = dt * erosion_.kd * (col.shear - erosion_.tau_c) * col.secant * area / col.top_layer;
    soil.eroded[p] += volume / std::pow(s, Dim - 1);
    if (soil.eroded[p] >= s) {  // detached: stress-free from now on
      soil.eroded[p] = std::numeric_limits<double>::infinity();
      soil.F[p] = Mat<Dim>::Identity();
      soil.log_jp[p] = 0;
      if (detached) detached->push_back(p);
    }
  }
  return taken;
}

template <int Dim>
void BedShear<Dim>::settle(Particles<Dim>& soil, std::size_t p, double dt) const {
  auto& x = soil.x[p];
  x += dt * erosion_.settling_velocity * down_;
  const auto& col = columns_[column_of(x)];
  const double s = side(soil, p);
  const bool calm = !(col.depth > 0) || col.shear <= erosion_.tau_c;
  if (col.has_bed && !calm && x[1] - 0.5 * s < col.bed) x[1] = col.bed + 0.5 * s;
}

template <int Dim>
void BedShear<Dim>::brake(Particles<Dim>& water, double dt, const std::vector<char>* free) const {
  for (std::size_t p = 0; p < water.size(); ++p) {
    const auto& col = columns_[column_of(water.x[p])];
    if (!(col.depth > 0) || !(free ? (*free)[p] : water.x[p][1] > col.bed)) continue;
    const double speed = col.velocity.norm();
    if (!(speed > 0)) continue;
    const double k = col.shear / (rho_w_ * col.depth * speed);
    water.v[p] -= (dt * k / (1 + dt * k)) * col.velocity;
  }
}

template <int Dim>
double BedShear<Dim>::eroded_volume(const Particles<Dim>& soil, std::size_t p) const {
  const double s = side(soil, p);
  return std::pow(s, Dim - 1) * std::min(soil.eroded[p], s);  // detached: e_p = infinity
}

template <int Dim>
double BedShear<Dim>::largest_shear() const {
  double most = 0;
  for (const auto& col : columns_) most = std::max(most, col.shear);
  return most;
}

template class BedShear<2>;
template class BedShear<3>;

}  // namespace suite::mpm2grid
