#include "solvers/foam_erosion_fem/run/breach_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

#include "core/errors.hpp"
#include "core/io/csv_series.hpp"
#include "solvers/breach/run/run_breach.hpp"
#include "solvers/breach/model/simulate.hpp"

namespace suite::foam_erosion {

namespace {

// Water volume per metre of crest upstream of the dam at `depth` above the foundation: the floor
// from the inlet to the upstream toe, and the wedge over the upstream face up to the crest; above
// the crest the section upstream of the crest edge.
double upstream_area(const FoamScene& s, double depth) {
  const double L = s.domain.upstream_length, m = s.dam.upstream_slope, H = s.dam.height;
  if (depth <= H) return L * depth + 0.5 * m * depth * depth;
  return L * depth + 0.5 * m * H * H + m * H * (depth - H);
}

}  // namespace

std::optional<breach::Scene> breach_scene_for(const FoamScene& s) {
  if (!s.soil.undrained_shear_strength || !s.soil.unit_weight) return std::nullopt;
  breach::Scene b;
  b.gravity = s.gravity;
  b.dam = s.dam;
  b.soil.kd = s.soil.kd * s.coupling.morphological_factor;
  b.soil.tau_c = s.soil.tau_c;
  b.soil.s_u = *s.soil.undrained_shear_strength;
  b.soil.gamma_t = *s.soil.unit_weight;
  b.soil.grain_roughness = breach::Soil::kDefaultGrainRoughness;  // bare soil, as a breach scene without it
  // The stage-storage as a table fine enough that its piecewise-constant area follows the
  // wedge's linear growth within 1/64 of the domain height.
  constexpr int rows = 64;
  std::vector<double> levels, volumes;
  for (int i = 0; i <= rows; ++i) {
    const double depth = s.domain.height * i / rows;
    levels.push_back(s.dam.foundation + depth);
    volumes.push_back(upstream_area(s, depth) * s.dam.crest_length);
  }
  b.reservoir.storage = breach::StageStorage::table(levels, volumes);
  b.reservoir.initial_level = s.initial_level;
  b.inflow = s.inflow;
  b.breach.initial_width = breach::BreachSettings::default_initial_width(s.dam);
  b.breach.face_roughness = b.soil.grain_roughness;
  b.breach.formation_depth = breach::BreachSettings::default_formation_depth(s.dam);
  b.time.start = 0.0;
  b.time.end = s.time.end;
  b.time.max_step = s.time.end / 50.0;
  b.output_interval = s.time.end / 400.0;
  if (const auto problem = b.cross_section_problem())
    throw InputError(fmt::format("the breach model refuses this dam for the comparison run: {}.{} {}; remove "
                                 "soil.undrained_shear_strength to run without it",
                                 problem->section, problem->key, problem->text));
  return b;
}

bool write_breach_comparison(const FoamScene& s, const std::filesystem::path& out, Summary& summary, Logger& log) {
  const auto scene = breach_scene_for(s);
  if (!scene) {
    log.info("no breach-model comparison: the scene gives no soil.undrained_shear_strength and soil.unit_weight");
    return false;
  }
  const auto dir = out / "breach_model";
  std::filesystem::create_directories(dir);
  io::CsvSeries csv(dir / "hydrograph.csv", breach::hydrograph_columns());
  const auto result = breach::simulate(*scene, [&](const breach::Sample& sample) { csv.append(breach::hydrograph_row(sample)); });
  breach::make_summary(result).write(dir / "summary.json");
  summary.set("breach_model_peak_outflow", result.peak_outflow, "m^3/s");
  summary.set("breach_model_time_to_peak", result.time_to_peak, "s");
  summary.set("breach_model_outflow_volume", result.outflow_volume, "m^3");
  summary.set("breach_model_eroded_volume", result.eroded_volume, "m^3");
  summary.set("breach_model_final_stage", breach::stage_name(result.final_stage));
  log.info("breach model on the same dam (kd x {} over the same {} s): peak outflow {:.4g} m^3/s at {:.3g} s, {:.4g} "
           "m^3 out, {:.4g} m^3 eroded, ends in {} ({})",
           s.coupling.morphological_factor, s.time.end, result.peak_outflow, result.time_to_peak,
           result.outflow_volume, result.eroded_volume, breach::stage_name(result.final_stage), dir.string());
  return true;
}

}  // namespace suite::foam_erosion
