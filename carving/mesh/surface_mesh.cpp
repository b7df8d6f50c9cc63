// Measures of a triangle mesh (area, enclosed volume, closedness) and its binary PLY reader and writer.
#include "carving/mesh/surface_mesh.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "core/errors.hpp"

namespace suite::carving {

namespace {

// Bytes of one vertex record (three floats) and one face record (a uchar count and three ints).
constexpr std::size_t kVertexBytes = 12;
constexpr std::size_t kFaceBytes = 13;
// Records per buffered write or read, to keep the buffers small for large meshes.
constexpr std::size_t kChunkRecords = 1 << 16;
// A PLY header longer than this is not one of ours.
constexpr std::size_t kMaxHeaderBytes = 1 << 16;

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// Little-endian stores and loads, independent of the byte order of the machine.
void put_u32(unsigned char* out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out[b] = static_cast<unsigned char>(v >> (8 * b));
}
std::uint32_t get_u32(const unsigned char* in) {
  std::uint32_t v = 0;
  for (int b = 0; b < 4; ++b) v |= static_cast<std::uint32_t>(in[b]) << (8 * b);
  return v;
}

// Centre of the bounding box of the vertices (origin for an empty mesh).
Eigen::Vector3d bounding_box_centre(const SurfaceMesh& mesh) {
  if (mesh.vertices.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return 0.5 * (lo + hi);
}

// A name for the temporary file beside `file` that no other writer picks.
std::filesystem::path temporary_path(const std::filesystem::path& file) {
  std::random_device device;
  const auto tag = (static_cast<std::uint64_t>(device()) << 32) ^ device();
  return file.parent_path() / fmt::format(".{}.{:016x}.tmp", file.filename().string(), tag);
}

// Removes the temporary file unless it was renamed into place.
struct TemporaryFile {
  std::filesystem::path path;
  bool keep = false;
  ~TemporaryFile() {
    if (keep) return;
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
};

std::string reason_of_errno() {
  return std::strerror(errno);
}

}  // namespace

double surface_area(const SurfaceMesh& mesh) {
  double area = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    area += 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
  }
  return area;
}

double enclosed_volume(const SurfaceMesh& mesh) {
  // Coordinates relative to the middle of the mesh keep the terms small, so a mesh far from the
  // origin loses no digits to cancellation.
  const Eigen::Vector3d centre = bounding_box_centre(mesh);
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]] - centre;
    const Eigen::Vector3d b = mesh.vertices[t[1]] - centre;
    const Eigen::Vector3d c = mesh.vertices[t[2]] - centre;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6;
}

bool is_closed(const SurfaceMesh& mesh) {
  // Each directed edge a -> b becomes the key (min, max, direction). Sorted, the keys of a closed
  // oriented mesh come in pairs: the same edge once in each direction, and no edge a third time.
  const auto n = static_cast<long long>(mesh.vertices.size());
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      if (a < 0 || b < 0 || a >= n || b >= n || a == b) return false;
      const auto lo = static_cast<std::uint64_t>(std::min(a, b));
      const auto hi = static_cast<std::uint64_t>(std::max(a, b));
      keys.push_back((lo << 32) | (hi << 1) | (a > b ? 1u : 0u));
    }
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 0; i < keys.size(); i += 2) {
    if (i + 1 >= keys.size()) return false;
    const std::uint64_t first = keys[i], second = keys[i + 1];
    if ((first >> 1) != (second >> 1) || (first & 1) != 0 || (second & 1) != 1) return false;
    if (i + 2 < keys.size() && (keys[i + 2] >> 1) == (first >> 1)) return false;
  }
  return true;
}

void write_ply(const std::filesystem::path& file, const SurfaceMesh& mesh) {
  const auto n_vertices = mesh.vertices.size();
  for (const auto& t : mesh.triangles) {
    for (int v : t) {
      if (v < 0 || static_cast<std::size_t>(v) >= n_vertices) {
        throw std::invalid_argument(
            fmt::format("write_ply: triangle index {} is outside the {} vertices of the mesh", v, n_vertices));
      }
    }
  }

  const auto folder = file.parent_path();
  std::error_code ec;
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec)) {
    throw InputError(
        fmt::format("cannot write mesh file {}: folder {} does not exist", file.string(), folder.string()));
  }
  TemporaryFile temporary{temporary_path(file)};
  File out(std::fopen(temporary.path.c_str(), "wb"));
  if (!out) throw InputError(fmt::format("cannot write mesh file {}: {}", file.string(), reason_of_errno()));

  const std::string header = fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment surface mesh, mm\nelement vertex {}\nproperty float x\n"
      "property float y\nproperty float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
      n_vertices, mesh.triangles.size());
  bool ok = std::fwrite(header.data(), 1, header.size(), out.get()) == header.size();

  std::vector<unsigned char> buffer;
  for (std::size_t first = 0; ok && first < n_vertices; first += kChunkRecords) {
    const std::size_t count = std::min(kChunkRecords, n_vertices - first);
    buffer.resize(count * kVertexBytes);
    for (std::size_t i = 0; i < count; ++i) {
      const Eigen::Vector3d& v = mesh.vertices[first + i];
      for (int axis = 0; axis < 3; ++axis) {
        put_u32(&buffer[i * kVertexBytes + 4 * axis], std::bit_cast<std::uint32_t>(static_cast<float>(v[axis])));
      }
    }
    ok = std::fwrite(buffer.data(), 1, buffer.size(), out.get()) == buffer.size();
  }
  for (std::size_t first = 0; ok && first < mesh.triangles.size(); first += kChunkRecords) {
    const std::size_t count = std::min(kChunkRecords, mesh.triangles.size() - first);
    buffer.resize(count * kFaceBytes);
    for (std::size_t i = 0; i < count; ++i) {
      unsigned char* record = &buffer[i * kFaceBytes];
      record[0] = 3;
      for (int c = 0; c < 3; ++c) {
        put_u32(record + 1 + 4 * c, static_cast<std::uint32_t>(mesh.triangles[first + i][c]));
      }
    }
    ok = std::fwrite(buffer.data(), 1, buffer.size(), out.get()) == buffer.size();
  }
  if (!ok || std::fflush(out.get()) != 0) {
    throw InputError(fmt::format("cannot write mesh file {}: {}", file.string(), reason_of_errno()));
  }
  if (std::fclose(out.release()) != 0) {
    throw InputError(fmt::format("cannot write mesh file {}: {}", file.string(), reason_of_errno()));
  }
  std::filesystem::rename(temporary.path, file, ec);
  if (ec) throw InputError(fmt::format("cannot write mesh file {}: {}", file.string(), ec.message()));
  temporary.keep = true;
}

SurfaceMesh read_ply(const std::filesystem::path& file) {
  const auto fail = [&](const std::string& what) {
    return InputError(
        fmt::format("mesh file {}: {} (expected binary little-endian PLY with float x y z vertices and triangle faces)",
                    file.string(), what));
  };
  File in(std::fopen(file.c_str(), "rb"));
  if (!in) throw InputError(fmt::format("cannot read mesh file {}: {}", file.string(), reason_of_errno()));

  // The header: text lines up to "end_header".
  std::vector<std::string> lines;
  std::size_t header_bytes = 0;
  std::string line;
  while (lines.empty() || lines.back() != "end_header") {
    const int c = std::fgetc(in.get());
    if (c == EOF) throw fail("the header has no end_header line");
    if (++header_bytes > kMaxHeaderBytes) throw fail("the header is too long");
    if (c == '\n') {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines.push_back(line);
      line.clear();
    } else {
      line.push_back(static_cast<char>(c));
    }
  }

  // Keep the lines that describe data, and check they are the ones write_ply writes.
  std::vector<std::vector<std::string>> words;
  for (const auto& text : lines) {
    std::istringstream stream(text);
    std::vector<std::string> w;
    for (std::string word; stream >> word;) w.push_back(word);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    words.push_back(std::move(w));
  }
  using Words = std::vector<std::string>;
  const auto is_float = [](const std::string& t) { return t == "float" || t == "float32"; };
  const auto is_uchar = [](const std::string& t) { return t == "uchar" || t == "uint8"; };
  const auto is_int = [](const std::string& t) { return t == "int" || t == "int32"; };
  const auto count_of = [&](const Words& w, const char* element) -> long long {
    if (w.size() != 3 || w[0] != "element" || w[1] != element) throw fail(fmt::format("no '{}' element", element));
    try {
      std::size_t used = 0;
      const long long count = std::stoll(w[2], &used);
      if (used == w[2].size() && count >= 0 && count <= INT_MAX) return count;
    } catch (const std::exception&) {
    }
    throw fail(fmt::format("bad {} count '{}'", element, w[2]));
  };
  if (words.size() != 9 || words[0] != Words{"ply"} || words[1] != Words{"format", "binary_little_endian", "1.0"}) {
    throw fail("unexpected header");
  }
  const long long n_vertices = count_of(words[2], "vertex");
  for (int axis = 0; axis < 3; ++axis) {
    const Words& w = words[3 + axis];
    const std::string name(1, "xyz"[axis]);
    if (w.size() != 3 || w[0] != "property" || !is_float(w[1]) || w[2] != name) {
      throw fail(fmt::format("vertex property {} is not 'property float {}'", axis + 1, name));
    }
  }
  const long long n_faces = count_of(words[6], "face");
  const Words& list = words[7];
  if (list.size() != 5 || list[0] != "property" || list[1] != "list" || !is_uchar(list[2]) || !is_int(list[3]) ||
      (list[4] != "vertex_indices" && list[4] != "vertex_index")) {
    throw fail("the face property is not 'property list uchar int vertex_indices'");
  }
  if (words[8] != Words{"end_header"}) throw fail("unexpected header line after the face property");

  // The body must have exactly the size the header announces (all faces are triangles).
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  const auto expected = header_bytes + static_cast<std::uintmax_t>(n_vertices) * kVertexBytes +
                        static_cast<std::uintmax_t>(n_faces) * kFaceBytes;
  if (ec || size != expected) {
    throw fail(fmt::format("{} bytes where {} vertices and {} triangles take {}", ec ? 0 : size, n_vertices, n_faces,
                           expected));
  }

  SurfaceMesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(n_vertices));
  mesh.triangles.resize(static_cast<std::size_t>(n_faces));
  std::vector<unsigned char> buffer;
  for (std::size_t first = 0; first < mesh.vertices.size(); first += kChunkRecords) {
    const std::size_t count = std::min(kChunkRecords, mesh.vertices.size() - first);
    buffer.resize(count * kVertexBytes);
    if (std::fread(buffer.data(), 1, buffer.size(), in.get()) != buffer.size())
      throw fail("the vertices are cut short");
    for (std::size_t i = 0; i < count; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        mesh.vertices[first + i][axis] = std::bit_cast<float>(get_u32(&buffer[i * kVertexBytes + 4 * axis]));
      }
    }
  }
  for (std::size_t first = 0; first < mesh.triangles.size(); first += kChunkRecords) {
    const std::size_t count = std::min(kChunkRecords, mesh.triangles.size() - first);
    buffer.resize(count * kFaceBytes);
    if (std::fread(buffer.data(), 1, buffer.size(), in.get()) != buffer.size()) throw fail("the faces are cut short");
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned char* record = &buffer[i * kFaceBytes];
      if (record[0] != 3) throw fail(fmt::format("face {} has {} corners, not 3", first + i, int{record[0]}));
      for (int c = 0; c < 3; ++c) {
        const auto index = static_cast<std::int32_t>(get_u32(record + 1 + 4 * c));
        if (index < 0 || index >= n_vertices) {
          throw fail(fmt::format("face {} refers to vertex {} of {}", first + i, index, n_vertices));
        }
        mesh.triangles[first + i][c] = index;
      }
    }
  }
  return mesh;
}

}  // namespace suite::carving
