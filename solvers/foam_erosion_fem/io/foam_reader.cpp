#include "solvers/foam_erosion_fem/io/foam_reader.hpp"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/io/atomic_file.hpp"

namespace suite::foam_erosion {

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw FoamReadError(fmt::format("cannot read OpenFOAM file {}", p.string()));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A cursor over an OpenFOAM file's text: whitespace and comments skipped between tokens.
class Scanner {
 public:
  Scanner(const std::string& text, fs::path file) : t_(text), file_(std::move(file)) {}

  void skip() {
    for (;;) {
      while (i_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[i_]))) ++i_;
      if (t_.compare(i_, 2, "//") == 0) {
        while (i_ < t_.size() && t_[i_] != '\n') ++i_;
      } else if (t_.compare(i_, 2, "/*") == 0) {
        const auto e = t_.find("*/", i_ + 2);
        i_ = e == std::string::npos ? t_.size() : e + 2;
      } else {
        return;
      }
    }
  }
  bool at_end() {
    skip();
    return i_ >= t_.size();
  }
  char peek() {
    skip();
    return i_ < t_.size() ? t_[i_] : '\0';
  }
  void expect(char c) {
    if (peek() != c) fail(fmt::format("expected '{}'", c));
    ++i_;
  }
  // A word: anything up to whitespace or punctuation; quoted strings keep their quotes.
  std::string word() {
    skip();
    const std::size_t s = i_;
    if (i_ < t_.size() && t_[i_] == '"') {
      const auto e = t_.find('"', i_ + 1);
      i_ = e == std::string::npos ? t_.size() : e + 1;
      return t_.substr(s, i_ - s);
    }
    while (i_ < t_.size() && !std::isspace(static_cast<unsigned char>(t_[i_])) &&
           std::string_view("(){};[]").find(t_[i_]) == std::string_view::npos)
      ++i_;
    if (i_ == s) fail("expected a word");
    return t_.substr(s, i_ - s);
  }
  double number() {
    skip();
    const char* b = t_.c_str() + i_;
    char* e = nullptr;
    const double v = std::strtod(b, &e);
    if (e == b) fail("expected a number");
    i_ += static_cast<std::size_t>(e - b);
    return v;
  }
  long count() {
    const double v = number();
    if (v < 0 || v != static_cast<double>(static_cast<long>(v))) fail("expected a list size");
    return static_cast<long>(v);
  }
  // Skips one value: a word, or a balanced (...) / {...} / [...] group.
  void skip_value() {
    const char c = peek();
    if (c == '(' || c == '{' || c == '[') {
      const char close = c == '(' ? ')' : c == '{' ? '}' : ']';
      int depth = 0;
      char open = c;
      for (; i_ < t_.size(); ++i_) {
        if (t_[i_] == open) ++depth;
        if (t_[i_] == close && --depth == 0) {
          ++i_;
          return;
        }
      }
      fail("unbalanced brackets");
    }
    word();
  }
  // Skips the FoamFile header dictionary if it is next.
  void skip_header() {
    const std::size_t s = i_;
    if (!at_end() && word() == "FoamFile") {
      skip_value();
    } else {
      i_ = s;
    }
  }
  // Moves to just after the top-level keyword `key` (at dictionary depth 0 of the current
  // level); false if the level ends first.
  bool find_key(const std::string& key) {
    while (!at_end()) {
      const char c = peek();
      if (c == '}') return false;
      if (c == ';') {
        ++i_;
        continue;
      }
      if (c == '(' || c == '{' || c == '[') {
        skip_value();
        continue;
      }
      const std::string w = word();
      if (w == key || w == "\"" + key + "\"") return true;
      // skip the entry's value up to its ';' or its dictionary
      while (!at_end()) {
        const char d = peek();
        if (d == ';') {
          ++i_;
          break;
        }
        if (d == '{') {
          skip_value();
          break;
        }
        if (d == '(' || d == '[') {
          skip_value();
          continue;
        }
        if (d == '}') return false;
        word();
      }
    }
    return false;
  }
  std::size_t pos() const { return i_; }
  [[noreturn]] void fail(const std::string& what) const {
    const auto line = 1 + std::count(t_.begin(), t_.begin() + static_cast<long>(std::min(i_, t_.size())), '\n');
    throw FoamReadError(fmt::format("{}:{}: {} (reading the file OpenFOAM wrote; was it written with "
                                    "writeFormat ascii and not compressed?)",
                                    file_.string(), line, what));
  }

 private:
  const std::string& t_;
  fs::path file_;
  std::size_t i_ = 0;
};

// One value of `components` numbers: "x" or "(x y z)".
void read_value(Scanner& s, int components, std::vector<double>& out) {
  if (components == 1) {
    out.push_back(s.number());
    return;
  }
  s.expect('(');
  for (int c = 0; c < components; ++c) out.push_back(s.number());
  s.expect(')');
}

// "N ( v v ... )" or "N{v}" after an optional "List<type>" word.
std::vector<double> read_list(Scanner& s, int components) {
  const long n = s.count();
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(n) * components);
  if (s.peek() == '{') {
    s.expect('{');
    std::vector<double> one;
    read_value(s, components, one);
    s.expect('}');
    for (long i = 0; i < n; ++i) out.insert(out.end(), one.begin(), one.end());
    return out;
  }
  s.expect('(');
  for (long i = 0; i < n; ++i) read_value(s, components, out);
  s.expect(')');
  return out;
}

// The value after a field keyword: "uniform v" or "nonuniform List<T> N(...)".
FieldValues read_field_entry(Scanner& s, int components, std::size_t size) {
  FieldValues f;
  f.components = components;
  const std::string kind = s.word();
  if (kind == "uniform") {
    std::vector<double> one;
    read_value(s, components, one);
    for (std::size_t i = 0; i < size; ++i) f.values.insert(f.values.end(), one.begin(), one.end());
  } else if (kind == "nonuniform") {
    s.word();  // List<scalar> / List<vector>
    f.values = read_list(s, components);
  } else {
    s.fail(fmt::format("expected 'uniform' or 'nonuniform', found '{}'", kind));
  }
  if (f.size() != size)
    s.fail(fmt::format("the field has {} values where {} were expected (does it belong to this mesh?)", f.size(), size));
  return f;
}

}  // namespace

PolyMesh PolyMesh::read(const fs::path& dir) {
  PolyMesh m;
  {
    const fs::path p = dir / "points";
    const std::string text = slurp(p);
    Scanner s(text, p);
    s.skip_header();
    const auto v = read_list(s, 3);
    m.points.resize(v.size() / 3);
    for (std::size_t i = 0; i < m.points.size(); ++i) m.points[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
  }
  {
    const std::string text = slurp(dir / "faces");
    Scanner s(text, dir / "faces");
    s.skip_header();
    const long n = s.count();
    m.faces.resize(static_cast<std::size_t>(n));
    s.expect('(');
    for (auto& f : m.faces) {
      const long k = s.count();
      s.expect('(');
      f.resize(static_cast<std::size_t>(k));
      for (auto& p : f) p = static_cast<int>(s.count());
      s.expect(')');
    }
    s.expect(')');
  }
  {
    const std::string text = slurp(dir / "owner");
    Scanner s(text, dir / "owner");
    s.skip_header();
    const auto v = read_list(s, 1);
    m.owner.assign(v.begin(), v.end());
  }
  {
    const std::string text = slurp(dir / "neighbour");
    Scanner s(text, dir / "neighbour");
    s.skip_header();
    const auto v = read_list(s, 1);
    m.neighbour.assign(v.begin(), v.end());
  }
  {
    const std::string text = slurp(dir / "boundary");
    Scanner s(text, dir / "boundary");
    s.skip_header();
    const long n = s.count();
    s.expect('(');
    for (long i = 0; i < n; ++i) {
      PatchInfo p;
      p.name = s.word();
      s.expect('{');
      while (s.peek() != '}') {
        const std::string key = s.word();
        if (key == "type") p.type = s.word();
        else if (key == "nFaces") p.faces = static_cast<int>(s.count());
        else if (key == "startFace") p.start_face = static_cast<int>(s.count());
        else
          while (s.peek() != ';') s.skip_value();
        s.expect(';');
      }
      s.expect('}');
      m.patches.push_back(p);
    }
  }
  return m;
}

const PatchInfo& PolyMesh::patch(const std::string& name) const {
  for (const auto& p : patches)
    if (p.name == name) return p;
  throw FoamReadError(fmt::format("the mesh has no patch '{}'", name));
}

int PolyMesh::cells() const {
  int n = 0;
  for (int o : owner) n = std::max(n, o + 1);
  return n;
}

std::vector<Eigen::Vector3d> PolyMesh::cell_centres() const {
  const auto n = static_cast<std::size_t>(cells());
  std::vector<std::vector<int>> points(n);
  const auto add = [&](int cell, int face) {
    auto& p = points[static_cast<std::size_t>(cell)];
    for (int q : faces[static_cast<std::size_t>(face)]) p.push_back(q);
  };
  for (std::size_t f = 0; f < owner.size(); ++f) add(owner[f], static_cast<int>(f));
  for (std::size_t f = 0; f < neighbour.size(); ++f) add(neighbour[f], static_cast<int>(f));
  std::vector<Eigen::Vector3d> centres(n, Eigen::Vector3d::Zero());
  for (std::size_t c = 0; c < n; ++c) {
    auto& p = points[c];
    std::sort(p.begin(), p.end());
    p.erase(std::unique(p.begin(), p.end()), p.end());
    for (int q : p) centres[c] += this->points[static_cast<std::size_t>(q)];
    if (!p.empty()) centres[c] /= static_cast<double>(p.size());
  }
  return centres;
}

std::vector<double> PolyMesh::cell_volumes() const {
  std::vector<double> v(static_cast<std::size_t>(cells()), 0.0);
  for (std::size_t f = 0; f < owner.size(); ++f) {
    const double flux = face_centre(static_cast<int>(f)).dot(face_area(static_cast<int>(f))) / 3.0;
    v[static_cast<std::size_t>(owner[f])] += flux;
    if (f < neighbour.size()) v[static_cast<std::size_t>(neighbour[f])] -= flux;
  }
  return v;
}

Eigen::Vector3d PolyMesh::face_centre(int face) const {
  const auto& f = faces[static_cast<std::size_t>(face)];
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int q : f) c += points[static_cast<std::size_t>(q)];
  return c / static_cast<double>(f.size());
}

Eigen::Vector3d PolyMesh::face_area(int face) const {
  // Sum of the triangles fanned from the centre; OpenFOAM orders a face's points so that the
  // right-hand normal points out of its owner.
  const auto& f = faces[static_cast<std::size_t>(face)];
  const Eigen::Vector3d c = face_centre(face);
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Eigen::Vector3d a = points[static_cast<std::size_t>(f[i])] - c;
    const Eigen::Vector3d b = points[static_cast<std::size_t>(f[(i + 1) % f.size()])] - c;
    s += 0.5 * a.cross(b);
  }
  return s;
}

FieldValues read_internal_field(const fs::path& file, int components, std::size_t size) {
  const std::string text = slurp(file);
  Scanner s(text, file);
  s.skip_header();
  if (!s.find_key("internalField")) s.fail("no internalField entry");
  return read_field_entry(s, components, size);
}

namespace {

// Moves the scanner to just after boundaryField.<patch>'s keyword.
void seek_patch(Scanner& s, const std::string& patch) {
  s.skip_header();
  if (!s.find_key("boundaryField")) s.fail("no boundaryField entry");
  s.expect('{');
  if (!s.find_key(patch)) s.fail(fmt::format("no entry for patch '{}' in boundaryField", patch));
}

}  // namespace

FieldValues read_patch_value(const fs::path& file, const std::string& patch, int components, std::size_t size) {
  const std::string text = slurp(file);
  Scanner s(text, file);
  seek_patch(s, patch);
  s.expect('{');
  if (!s.find_key("value")) s.fail(fmt::format("patch '{}' has no value entry", patch));
  return read_field_entry(s, components, size);
}


std::vector<fs::path> time_directories(const fs::path& case_dir) {
  std::vector<std::pair<double, fs::path>> found;
  for (const auto& e : fs::directory_iterator(case_dir)) {
    if (!e.is_directory()) continue;
    const std::string name = e.path().filename().string();
    char* end = nullptr;
    const double t = std::strtod(name.c_str(), &end);
    if (end != name.c_str() && *end == '\0') found.emplace_back(t, e.path());
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<fs::path> out;
  for (auto& f : found) out.push_back(f.second);
  return out;
}

fs::path latest_time_directory(const fs::path& case_dir) {
  const auto all = time_directories(case_dir);
  if (all.empty()) throw FoamReadError(fmt::format("case {} has no time directory", case_dir.string()));
  return all.back();
}

void write_internal_scalar_field(const fs::path& file, const std::vector<double>& values) {
  const std::string text = slurp(file);
  const auto at = text.find("\ninternalField");
  const auto end = at == std::string::npos ? at : text.find(';', at);
  if (end == std::string::npos)
    throw FoamReadError(fmt::format("{}: no 'internalField ...;' entry to replace", file.string()));
  std::string list = fmt::format("internalField   nonuniform List<scalar> {}\n(\n", values.size());
  for (double v : values) list += fmt::format("{:.12g}\n", v);
  list += ")\n";
  io::write_file_atomic(file, text.substr(0, at + 1) + list + text.substr(end));
}

}  // namespace suite::foam_erosion
