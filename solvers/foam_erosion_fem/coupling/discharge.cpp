#include "solvers/foam_erosion_fem/coupling/discharge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "core/io/atomic_file.hpp"
#include "solvers/foam_erosion_fem/io/foam_reader.hpp"

namespace suite::foam_erosion {

namespace fs = std::filesystem;

DischargeSeries read_discharge(const fs::path& case_dir, const std::string& section) {
  const fs::path dir = case_dir / "postProcessing" / (section + "Discharge");
  std::vector<std::pair<double, fs::path>> files;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir)) {
      const fs::path f = entry.path() / "surfaceFieldValue.dat";
      char* end = nullptr;
      const std::string name = entry.path().filename().string();
      const double start = std::strtod(name.c_str(), &end);
      if (end && *end == '\0' && fs::exists(f)) files.emplace_back(start, f);
    }
  if (files.empty())
    throw FoamReadError(fmt::format("no discharge record of section '{}' in {} (the case's {}Discharge function object "
                                    "writes it while interFoam runs)",
                                    section, dir.string(), section));
  std::sort(files.begin(), files.end());
  std::map<double, std::pair<double, double>> rows;
  for (const auto& [start, f] : files) {
    rows.erase(rows.lower_bound(start), rows.end());
    std::ifstream in(f);
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (line.empty() || line[0] == '#') continue;
      std::istringstream is(line);
      double t = 0, water = 0, mixture = 0;
      if (!(is >> t >> water >> mixture))
        throw FoamReadError(fmt::format("{}:{}: expected 'time sum(alphaPhi0.water) sum(phi)', found '{}'",
                                        f.string(), number, line));
      rows[t] = {water, mixture};
    }
  }
  DischargeSeries s;
  for (const auto& [t, v] : rows) {
    s.time.push_back(t);
    s.water.push_back(v.first);
    s.mixture.push_back(v.second);
  }
  return s;
}

void write_discharge_csv(const fs::path& file, const std::vector<std::string>& sections,
                         const std::vector<DischargeSeries>& series, double scale) {
  std::vector<std::map<double, double>> by_time(series.size());
  for (std::size_t k = 0; k < series.size(); ++k)
    for (std::size_t i = 0; i < series[k].time.size(); ++i) by_time[k][series[k].time[i]] = series[k].water[i];
  std::string out = "time_s";
  for (const auto& s : sections) out += "," + s + "_Q_m3_s";
  out += "\n";
  if (!series.empty())
    for (const auto& [t, first] : by_time[0]) {
      std::string row = fmt::format("{:.9g}", t);
      bool complete = true;
      for (std::size_t k = 0; k < series.size() && complete; ++k) {
        const auto it = by_time[k].find(t);
        if (it == by_time[k].end()) complete = false;
        else row += fmt::format(",{:.9g}", (sections[k] == "inlet" ? -1.0 : 1.0) * scale * it->second + 0.0);  // no -0
      }
      if (complete) out += row + "\n";
    }
  io::write_file_atomic(file, out);
}

double time_mean(const std::vector<double>& time, const std::vector<double>& values, double t0, double t1) {
  double sum = 0.0, span = 0.0;
  for (std::size_t i = 1; i < time.size(); ++i) {
    if (time[i] <= t0 || time[i] > t1) continue;
    const double dt = time[i] - std::max(time[i - 1], t0);
    sum += dt * values[i];
    span += dt;
  }
  return span > 0.0 ? sum / span : 0.0;
}

}  // namespace suite::foam_erosion
