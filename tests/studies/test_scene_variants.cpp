// The breach model reads its scene once per study (breach::SceneVariants) and sets each
// evaluation's values on a copy. These tests hold it to what reading the scene file again with
// the values as overrides gives: the same scene bit for bit (the same run summary, every number
// printed to round trip), or no scene, leaving the file read to give the error. Then whole
// studies give the same table and failure reasons either way.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "core/config/config.hpp"
#include "core/log/logger.hpp"
#include "core/mpi/comm.hpp"
#include "solvers/breach/run/run_breach.hpp"
#include "solvers/breach/model/scene_variants.hpp"
#include "solvers/breach/model/simulate.hpp"
#include "studies/run/study.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

namespace fs = std::filesystem;
using suite::breach::Scene;
using suite::breach::SceneVariants;
using suite::config::Config;
using suite::testing::read_file;

const std::string kInternalErosionScene = SUITE_BREACH_EXAMPLES "/scale_family_internal_erosion/clay_CL_scale0.yaml";

// Values in and out of every key's range and kind: bare SI numbers around the scenes' sizes
// (the scale-0 dam is 1.22 m high), values with units of each dimension the keys take, and
// text that is not a plain number.
const std::vector<std::string> kValues = {"0",
                                          "0.03",
                                          "0.3",
                                          "0.5",
                                          "0.9",
                                          "1",
                                          "1.5",
                                          "3",
                                          "4.5",
                                          "7.5",
                                          "12",
                                          "40",
                                          "150",
                                          "1e4",
                                          "1e9",
                                          "-1",
                                          "-0.2 m",
                                          "2 ft",
                                          "0.75 m",
                                          "40 ft",
                                          "3 kg",
                                          "20 cfs",
                                          "0.5 m^3/s",
                                          "0.2 psf",
                                          "120 psf",
                                          "120 lbf/ft^3",
                                          "300 (ft/h)/psf",
                                          "25 cm^3/(N s)",
                                          "1e-5 m^3/(N s)",
                                          "abc",
                                          "[1, 2]",
                                          "'2'",
                                          "2 # c",
                                          "+2",
                                          "null",
                                          "- 2",
                                          " 4 ",
                                          "2 m: 3",
                                          "1e400",
                                          "inf"};

// Text the variants may leave to the file read although it reads: not starting with a digit,
// '.' or '-', or holding characters YAML might treat specially.
bool plain(const std::string& text) {
  const auto b = text.find_first_not_of(' ');
  if (b == std::string::npos || !(std::isdigit(static_cast<unsigned char>(text[b])) || text[b] == '-')) return false;
  return text.find_first_of("#:[]'") == std::string::npos && text.rfind("- ", b) != b;
}

// The run's summary, every number printed to round trip, or the error that stopped it.
std::string summary_of(const Scene& scene) {
  try {
    return suite::breach::make_summary(suite::breach::simulate(scene)).json().dump();
  } catch (const std::exception& e) {
    return std::string("error: ") + e.what();
  }
}

// Every number of a scene, printed to round trip: its fields, and its storage, inflow and
// spillway sampled (they keep their parameters private). Runs of some of the scenes the values
// below make would take long (a 1e9 m crest), so the key-by-key test compares scenes this way.
std::string fingerprint(const Scene& s) {
  std::string out = fmt::format("g {} dam {} {} {} {} {} {} soil {} {} {} {} {} level {} ", s.gravity, s.dam.height,
                                s.dam.crest_width, s.dam.crest_length, s.dam.upstream_slope, s.dam.downstream_slope,
                                s.dam.foundation, s.soil.kd, s.soil.tau_c, s.soil.s_u, s.soil.gamma_t,
                                s.soil.grain_roughness, s.reservoir.initial_level);
  out += fmt::format("breach {} {} {} {} {} {} {} ", s.breach.initial_width, s.breach.side_slope,
                     s.breach.face_roughness, s.breach.formation_depth, s.breach.headcut.jet_friction,
                     s.breach.headcut.jet_diffusion, s.breach.headcut.critical_height_factor);
  out += fmt::format("pipe {} {} {} {} {} ", s.internal_erosion.enabled, s.internal_erosion.elevation,
                     s.internal_erosion.initial_diameter, s.internal_erosion.entrance_loss,
                     s.internal_erosion.collapse_fraction);
  out += fmt::format("time {} {} {} {} {} {} {} bottom {} kind {} ", s.time.start, s.time.end, s.time.adaptive,
                     s.time.tolerance, s.time.fixed_step, s.time.max_step, s.output_interval,
                     s.reservoir.storage.bottom(), static_cast<int>(s.inflow.kind()));
  for (double h : {-1.0, 0.0, 0.3, 1.0, 2.5, 7.0, 11.0, 13.0, 40.0})
    out +=
        fmt::format("{} {} {} ", s.reservoir.storage.volume(h), s.reservoir.storage.area(h), s.reservoir.spillway(h));
  for (double t : {0.0, 100.0, 5000.0, 21600.0, 40000.0, 72000.0, 1e5})
    out += fmt::format("{} {} ", s.inflow(t), s.inflow.cumulative(t));
  for (double t : s.inflow.breakpoints()) out += fmt::format("{} ", t);
  return out;
}

// Every key with every value on the scene `path` with `base` overrides: where the variants give
// a scene, reading the file again gives the same scene; with `equivalent`, the variants also give
// one wherever the file reads and the value is plain. Returns the number of variants made.
int compare_every_key(const std::string& path, const std::vector<std::string>& base, bool equivalent) {
  const SceneVariants variants(Config::from_file(path, base));
  int made = 0;
  for (const auto& key : SceneVariants::keys()) {
    for (const auto& value : kValues) {
      const auto fast = variants.with({{key, value}});
      std::optional<Scene> slow;
      auto overrides = base;
      overrides.push_back(key + "=" + value);
      try {
        slow = Scene::read_complete(Config::from_file(path, overrides));
      } catch (const suite::InputError&) {
      }
      const std::string what = path + " with " + key + "=" + value;
      if (fast) {
        ++made;
        EXPECT_TRUE(slow) << what << ": the variants took a value the scene refuses";
        if (slow) {
          EXPECT_EQ(fingerprint(*fast), fingerprint(*slow)) << what;
        }
      } else if (equivalent && plain(value)) {
        EXPECT_FALSE(slow) << what << ": the scene reads, the variants refused it";
      }
    }
  }
  return made;
}

TEST(SceneVariants, EveryKeyGivesTheSceneTheFileGives) {
  // Internal erosion, triangular storm, power-law storage: every key has its section here.
  EXPECT_GT(compare_every_key(kInternalErosionScene, {}, true), 200);
  // Width and formation depth given (they no longer follow the dam), no internal erosion.
  EXPECT_GT(compare_every_key(SUITE_BREACH_DEFAULT_SCENE, {"breach.initial_width=20 m", "headcut.formation_depth=1 m"},
                              false),
            150);
  // A constant inflow and a storage table: the inflow's discharge is set, the power law's keys
  // are left to the file read.
  EXPECT_GT(compare_every_key(SUITE_BREACH_DEFAULT_SCENE,
                              {"inflow={type: constant, discharge: 50}",
                               "reservoir.storage={type: table, table: [[0, 0], [6, 1e6], [14, 7e6]]}"},
                              false),
            150);
}

TEST(SceneVariants, SeveralKeysAtOnceAsTheDissertationStudySetsThem) {
  const SceneVariants variants(Config::from_file(kInternalErosionScene));
  for (int scale = 0; scale <= 5; ++scale) {
    const double h = std::pow(2.0, scale + 2);  // ft
    const std::vector<std::pair<std::string, std::string>> set = {
        {"soil.erodibility", "860 (ft/h)/psf"},
        {"soil.undrained_shear_strength", "28.02 psf"},
        {"dam.height", fmt::format("{} ft", h)},
        {"dam.crest_width", fmt::format("{} ft", h / 5 + 10)},
        {"dam.crest_length", fmt::format("{} ft", 10 * h)},
        {"reservoir.storage.alpha", fmt::format("{}", 1000 * 0.3048 * h)},
        {"reservoir.initial_level", fmt::format("{} m", 0.95 * 0.3048 * h)},
        {"inflow.peak", fmt::format("{} m^3/s", 0.6 * std::pow(0.3048 * h, 2.5))},
        {"internal_erosion.elevation", fmt::format("{} ft", h / 4)},
        {"internal_erosion.initial_diameter", fmt::format("{} ft", h / 100)}};
    std::vector<std::string> overrides;
    for (const auto& [k, v] : set) overrides.push_back(k + "=" + v);
    const auto fast = variants.with(set);
    ASSERT_TRUE(fast) << "scale " << scale;
    EXPECT_EQ(summary_of(*fast), summary_of(Scene::read_complete(Config::from_file(kInternalErosionScene, overrides))))
        << "scale " << scale;
  }
}

// The dissertation's set over Kd (from a negative value, which the scene refuses), Us and Scale.
std::string spec(const std::string& read_scene, const std::string& scene = kInternalErosionScene) {
  return "variables:\n"
         "  - {name: Kd, lower: -400, upper: 1700}\n"
         "  - {name: Us, lower: 0.3, upper: 70}\n"
         "  - {name: Scale, lower: 0, upper: 5}\n"
         "method: {type: multidim, partitions: [3, 2, 5]}\n"
         "model:\n"
         "  type: breach\n"
         "  scene: " +
         scene +
         "\n"
         "  read_scene: " +
         read_scene +
         "\n"
         "  set:\n"
         "    soil.erodibility: \"{Kd} (ft/h)/psf\"\n"
         "    soil.undrained_shear_strength: \"{Us} psf\"\n"
         "    dam.height: \"{2**(Scale+2)} ft\"\n"
         "    dam.crest_width: \"{2**(Scale+2)/5 + 10} ft\"\n"
         "    dam.crest_length: \"{10*2**(Scale+2)} ft\"\n"
         "    reservoir.storage.alpha: \"{1000*0.3048*2**(Scale+2)}\"\n"
         "    reservoir.initial_level: \"{0.95*0.3048*2**(Scale+2)} m\"\n"
         "    inflow.peak: \"{0.6*(0.3048*2**(Scale+2))**2.5} m^3/s\"\n"
         "    internal_erosion.elevation: \"{2**(Scale+2)/4} ft\"\n"
         "    internal_erosion.initial_diameter: \"{2**(Scale+2)/100} ft\"\n"
         "  responses: [peak_outflow, time_to_peak, eroded_volume]\n"
         "output: {plot: false}\n";
}

suite::studies::StudyCounts run(const fs::path& dir, const std::string& text) {
  const suite::mpi::Comm self(MPI_COMM_SELF);
  suite::Logger log(self, "study", {suite::LogLevel::warn, false, nullptr});
  return suite::studies::run_study(Config::from_string(text, "study.yaml"), {dir, false, false}, log);
}

TEST(SceneVariants, StudyTableIsTheSameAsReadingTheSceneEveryEvaluation) {
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  const auto once = run(dir / "once", spec("once"));
  run(dir / "every", spec("every_evaluation"));
  EXPECT_EQ(once.points, 72u);
  EXPECT_EQ(once.failed, 18u) << "Kd = -400 is refused at each of the 18 (Us, Scale) points";
  EXPECT_EQ(read_file(dir / "once" / "tabular.dat"), read_file(dir / "every" / "tabular.dat"));
  const std::string csv = read_file(dir / "once" / "tabular.csv");
  EXPECT_EQ(csv, read_file(dir / "every" / "tabular.csv")) << "the same failure reasons";
  EXPECT_NE(csv.find("model.set 'soil.erodibility=-400 (ft/h)/psf'"), std::string::npos) << csv;
}

TEST(SceneVariants, ASceneThatNeedsTheStudysValuesStillRuns) {
  // The scene leaves out the erodibility the study sets: it reads only with the study's values,
  // so each evaluation reads it with them.
  const auto dir = suite::testing::scratch_dir(suite::mpi::Comm(MPI_COMM_SELF));
  std::string scene = read_file(kInternalErosionScene);
  const auto at = scene.find("  erodibility:");
  scene.erase(at, scene.find('\n', at) + 1 - at);
  std::ofstream(dir / "no_kd.yaml") << scene;
  const auto c = run(dir / "a", spec("once", (dir / "no_kd.yaml").string()));
  EXPECT_EQ(c.failed, 18u);
  run(dir / "b", spec("once"));
  EXPECT_EQ(read_file(dir / "a" / "tabular.dat"), read_file(dir / "b" / "tabular.dat"));
}

}  // namespace
