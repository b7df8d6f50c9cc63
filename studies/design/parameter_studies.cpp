#include "studies/design/parameter_studies.hpp"

#include <fmt/format.h>

#include <fstream>
#include <random>
#include <sstream>

#include "core/errors.hpp"

namespace suite::studies {

std::vector<Point> multidim_points(const std::vector<Variable>& vars, const std::vector<long long>& partitions) {
  const std::size_t n = vars.size();
  std::vector<double> start(n), step(n);
  std::size_t count = 1;
  for (std::size_t i = 0; i < n; ++i) {
    const long long p = partitions[i];
    start[i] = p ? vars[i].lower : vars[i].initial;
    step[i] = p ? (vars[i].upper - vars[i].lower) / static_cast<double>(p) : 0.0;
    count *= static_cast<std::size_t>(p + 1);
  }
  std::vector<Point> points;
  points.reserve(count);
  std::vector<long long> index(n, 0);
  for (std::size_t e = 0; e < count; ++e) {
    Point x(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = start[i] + static_cast<double>(index[i]) * step[i];
    points.push_back(std::move(x));
    for (std::size_t i = 0; i < n; ++i) {  // first index fastest
      if (++index[i] <= partitions[i]) break;
      index[i] = 0;
    }
  }
  return points;
}

std::vector<Point> vector_points(const Point& initial, const Point& step, long long num_steps) {
  std::vector<Point> points;
  for (long long k = 0; k <= num_steps; ++k) {
    Point x(initial.size());
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = initial[i] + static_cast<double>(k) * step[i];
    points.push_back(std::move(x));
  }
  return points;
}

std::vector<Point> centered_points(const Point& initial, const Point& step, const std::vector<long long>& steps) {
  std::vector<Point> points{initial};
  for (std::size_t i = 0; i < initial.size(); ++i)
    for (long long k = -steps[i]; k <= steps[i]; ++k) {
      if (k == 0) continue;
      Point x = initial;
      x[i] = initial[i] + static_cast<double>(k) * step[i];
      points.push_back(std::move(x));
    }
  return points;
}

namespace {

// One value for every variable, or one value meaning all of them.
template <class T>
std::vector<T> per_variable(const config::Section& s, const std::string& key, std::size_t n) {
  if (s.has(key)) {
    try {
      const auto one = s.get<T>(key);
      return std::vector<T>(n, one);
    } catch (const InputError&) {
    }
  }
  auto many = s.get<std::vector<T>>(key);
  if (many.size() != n) s.reject(key, fmt::format("give one value, or one per variable ({}), not {}", n, many.size()));
  return many;
}

std::vector<Point> read_list(const config::Section& s, std::size_t n) {
  std::vector<Point> points;
  if (s.has("file")) {
    const auto path = s.file("file");
    std::ifstream in(path);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      for (char& c : line)
        if (c == ',' || c == ';' || c == '\t') c = ' ';
      std::istringstream fields(line);
      Point x;
      double v;
      while (fields >> v) x.push_back(v);
      if (x.empty() && (line.find_first_not_of(' ') == std::string::npos || line[line.find_first_not_of(' ')] == '#'))
        continue;
      if (x.empty() && points.empty()) continue;  // a header line
      if (x.size() != n || !fields.eof())
        throw InputError(
            fmt::format("{}:{}: expected {} numbers (one per variable), got '{}'", path.string(), number, n, line));
      points.push_back(std::move(x));
    }
  } else {
    const auto flat = s.get<std::vector<double>>("points");
    if (flat.empty() || flat.size() % n) s.reject("points", fmt::format("give points of {} values each", n));
    for (std::size_t i = 0; i < flat.size(); i += n) points.emplace_back(flat.begin() + i, flat.begin() + i + n);
  }
  if (points.empty()) s.reject(s.has("file") ? "file" : "points", "the list holds no points");
  return points;
}

}  // namespace

Design read_design(const config::Section& s, const std::vector<Variable>& vars) {
  const std::size_t n = vars.size();
  Design d;
  d.method = s.choice("type", {"multidim", "vector", "centered", "list", "sampling", "sobol_indices", "morris"});
  for (const auto& v : vars) d.lower.push_back(v.lower), d.upper.push_back(v.upper);
  if (d.method == "sampling" || d.method == "sobol_indices" || d.method == "morris") {
    std::random_device entropy;
    d.seed = static_cast<std::uint64_t>(s.integer("seed", entropy() % 2147483647u, 1, 2147483647));
    std::vector<Distribution> marginals;
    for (const auto& v : vars) marginals.push_back(v.distribution);
    if (d.method == "sampling") {
      const std::string kind = s.choice("sample_type", {"lhs", "random", "sobol_sequence"}, "lhs");
      const auto samples = static_cast<std::size_t>(s.integer("samples", 100, 1, 100000000));
      std::vector<std::vector<double>> rank_correlation;
      if (s.has("rank_correlation")) {  // the Spearman matrix, one row per variable
        rank_correlation = s.table("rank_correlation", std::vector<std::string>(n, "1"));
        if (rank_correlation.size() != n)
          s.reject("rank_correlation", fmt::format("give {} rows, one per variable", n));
      }
      try {
        d.points = sample(marginals,
                          kind == "lhs"      ? SamplingKind::lhs
                          : kind == "random" ? SamplingKind::random
                                             : SamplingKind::sobol_sequence,
                          samples, d.seed, rank_correlation);
      } catch (const InputError& e) {
        s.reject(s.has("rank_correlation") ? "rank_correlation" : "sample_type", e.what());
      }
    } else if (d.method == "sobol_indices") {
      d.saltelli =
          saltelli_design(marginals, static_cast<std::size_t>(s.integer("samples", 1000, 2, 10000000)), d.seed);
      d.points = d.saltelli->points;
    } else {
      const auto levels = s.integer("levels", 4, 2, 1000);
      if (levels % 2 != 0)
        s.reject("levels",
                 "must be even (Morris's step is half the levels, so that every level is reached with "
                 "equal probability): give 4 (the default), 6, 8, ...");
      d.morris = morris_design(d.lower, d.upper, static_cast<std::size_t>(s.integer("trajectories", 10, 1, 100000)),
                               static_cast<std::size_t>(levels), d.seed);
      d.points = d.morris->points;
    }
    return d;
  }
  Point initial;
  for (const auto& v : vars) initial.push_back(v.initial);
  if (d.method == "multidim") {
    const auto p = per_variable<long long>(s, "partitions", n);
    for (long long pi : p)
      if (pi < 0) s.reject("partitions", "must be >= 0");
    d.points = multidim_points(vars, p);
  } else if (d.method == "vector") {
    const long long steps = s.integer("num_steps", 10, 0, 1000000);
    Point step(n);
    if (s.has("final_point") == s.has("step_vector"))
      s.reject(s.has("final_point") ? "step_vector" : "final_point", "give either final_point or step_vector");
    if (s.has("final_point")) {
      const auto fin = per_variable<double>(s, "final_point", n);
      for (std::size_t i = 0; i < n; ++i) step[i] = steps ? (fin[i] - initial[i]) / static_cast<double>(steps) : 0.0;
    } else {
      step = per_variable<double>(s, "step_vector", n);
    }
    d.points = vector_points(initial, step, steps);
  } else if (d.method == "centered") {
    d.points = centered_points(initial, per_variable<double>(s, "step_vector", n),
                               per_variable<long long>(s, "steps_per_variable", n));
  } else {
    d.points = read_list(s, n);
    for (std::size_t k = 0; k < d.points.size(); ++k)
      for (std::size_t i = 0; i < n; ++i)
        if (d.points[k][i] < vars[i].lower || d.points[k][i] > vars[i].upper)
          s.reject(s.has("file") ? "file" : "points",
                   fmt::format("point {} has {} = {}, outside its bounds [{}, {}]", k + 1, vars[i].name, d.points[k][i],
                               vars[i].lower, vars[i].upper));
  }
  return d;
}

}  // namespace suite::studies
