#include "carving/io/carve_input.hpp"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <string>

#include "core/errors.hpp"

namespace suite::carving {
namespace {

class Reader {
 public:
  explicit Reader(const std::filesystem::path& file) : file_(file), in_(file, std::ios::binary) {
    if (!in_) throw InputError(fmt::format("cannot read carving input '{}'", file.string()));
  }
  template <class T>
  T value(const std::string& what) {
    T v{};
    bytes(reinterpret_cast<char*>(&v), sizeof v, what);  // the file and this machine are little-endian
    return v;
  }
  void bytes(char* out, std::size_t n, const std::string& what) {
    in_.read(out, static_cast<std::streamsize>(n));
    if (static_cast<std::size_t>(in_.gcount()) != n)
      throw InputError(
          fmt::format("carving input '{}' ends inside {} (byte {}); the file is truncated or not in "
                      "the carve_input.dat format",
                      file_.string(), what, static_cast<long long>(offset_ + in_.gcount())));
    offset_ += n;
  }
  bool at_end() { return in_.peek() == std::char_traits<char>::eof(); }

 private:
  std::filesystem::path file_;
  std::ifstream in_;
  std::size_t offset_ = 0;
};

int checked_size(int v, int max, const std::filesystem::path& file, const std::string& what) {
  if (v < 1 || v > max)
    throw InputError(fmt::format("carving input '{}': {} = {} is outside 1..{}; is this a carve_input.dat file?",
                                 file.string(), what, v, max));
  return v;
}

}  // namespace

CarveInput read_carve_input(const std::filesystem::path& file) {
  Reader r(file);
  CarveInput c;
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a) n[a] = checked_size(r.value<std::int32_t>("the grid size"), 4096, file, "grid size");
  c.initial.resize(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
  r.bytes(reinterpret_cast<char*>(c.initial.data()), c.initial.size(), "the initial occupancy");
  const int m = checked_size(r.value<std::int32_t>("the view count"), 10000, file, "view count");
  for (int v = 0; v < m; ++v) {
    const std::string what = fmt::format("view {}", v);
    View view;
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 3; ++row) view.P(row, col) = r.value<double>(what + "'s projection matrix");
    view.width = checked_size(r.value<std::int32_t>(what + "'s mask width"), 1 << 16, file, what + " mask width");
    view.height = checked_size(r.value<std::int32_t>(what + "'s mask height"), 1 << 16, file, what + " mask height");
    std::vector<std::uint8_t> x_major(static_cast<std::size_t>(view.width) * view.height);
    r.bytes(reinterpret_cast<char*>(x_major.data()), x_major.size(), what + "'s mask");
    std::vector<std::uint8_t> rows(x_major.size());
    for (int x = 0; x < view.width; ++x)
      for (int y = 0; y < view.height; ++y)
        rows[static_cast<std::size_t>(y) * view.width + x] = x_major[static_cast<std::size_t>(x) * view.height + y];
    c.views.push_back(view);
    c.masks.emplace_back(view.width, view.height, std::move(rows));
  }
  for (int a = 0; a < 3; ++a) {
    c.box_mm[a] = r.value<double>("the box size");
    if (!(c.box_mm[a] > 0))
      throw InputError(fmt::format("carving input '{}': box size {} mm is not positive", file.string(), c.box_mm[a]));
  }
  if (!r.at_end())
    throw InputError(
        fmt::format("carving input '{}' has bytes after the box size; it is not in the "
                    "carve_input.dat format",
                    file.string()));
  c.grid.n = n;
  c.grid.lo = -c.box_mm / 2;
  c.grid.voxel = c.box_mm.cwiseQuotient(Eigen::Vector3d(n[0], n[1], n[2]));
  c.original = c.grid;
  c.original.lo += c.grid.voxel;
  return c;
}

}  // namespace suite::carving
