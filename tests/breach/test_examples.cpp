// The shipped example scenes (solvers/breach/examples): every one reads and runs, and the
// dissertation's synthetic family behaves as its WinDAM C study did: larger dams, larger peaks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/config/config.hpp"
#include "solvers/breach/model/simulate.hpp"

namespace {

using namespace suite::breach;
namespace fs = std::filesystem;
const fs::path kExamples = SUITE_BREACH_EXAMPLES;

Result run_file(const fs::path& file) {
  auto cfg = suite::config::Config::from_file(file);
  const Scene s = Scene::read(cfg.root());
  cfg.root().section_or_empty("output").get<bool>("plot", true);
  cfg.finish();
  return simulate(s);
}

TEST(BreachExamples, EveryExampleRuns) {
  int count = 0;
  for (const auto& e : fs::recursive_directory_iterator(kExamples)) {
    if (e.path().extension() != ".yaml") continue;
    const Result r = run_file(e.path());
    EXPECT_TRUE(std::isfinite(r.peak_outflow) && r.peak_outflow > 0.0) << e.path();
    EXPECT_LT(std::abs(r.mass_balance_error), 1e-12 * (r.inflow_volume + r.outflow_volume + 1.0)) << e.path();
    ++count;
  }
  EXPECT_EQ(count, 1 + 12 + 8) << "default scene, 2 x 6 family members, 8 Table 3.4 dams";
}

TEST(BreachExamples, ScaleFamilyPeaksRiseWithScale) {
  for (const char* material : {"silty_sand_SM", "clay_CL"}) {
    double last = 0.0;
    for (int s = 0; s <= 5; ++s) {
      const Result r = run_file(kExamples / "scale_family" / (std::string(material) + "_scale" + std::to_string(s) + ".yaml"));
      EXPECT_GT(r.peak_outflow, last) << material << " scale " << s;
      EXPECT_TRUE(r.failed()) << material << " scale " << s;
      last = r.peak_outflow;
    }
  }
}

}  // namespace
