#pragma once
// The breach model (solvers/breach) run on the same dam as a coupled foam-erosion run, for the
// issue's "coupled result beside the breach model's": the same dam block, inflow, initial level
// and flow time; the reservoir's stage-storage is that of the 2D section upstream of the dam
// (floor from the inlet to the upstream toe, then the upstream face, times the crest length);
// the erodibility is kd x the morphological factor, the same acceleration the coupled run
// applies to its erosion. The breach model needs s_u and the unit weight for its headcut stage:
// a scene without soil.undrained_shear_strength and soil.unit_weight gets no comparison.
//
// Writes `<out>/breach_model/hydrograph.csv` and `summary.json` (the breach executable's
// formats) and adds the comparison's numbers to the run's summary (breach_model_*).
#include <filesystem>
#include <optional>

#include "core/log/logger.hpp"
#include "core/run/run_record.hpp"
#include "solvers/breach/model/scene.hpp"
#include "solvers/foam_erosion_fem/scenes/foam_scene.hpp"

namespace suite::foam_erosion {

// The breach scene of the same dam, or none when the soil lacks s_u or the unit weight.
// InputError if the breach model refuses the combination (the message names the breach key).
std::optional<breach::Scene> breach_scene_for(const FoamScene& scene);

// Runs it (well under a second) and writes the outputs described above; false (and a log line
// saying which keys to add) when the scene has no comparison.
bool write_breach_comparison(const FoamScene& scene, const std::filesystem::path& out, Summary& summary, Logger& log);

}  // namespace suite::foam_erosion
