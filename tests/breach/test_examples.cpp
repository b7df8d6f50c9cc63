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
  const Scene s = Scene::read_complete(cfg);
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
  EXPECT_EQ(count, 1 + 2 * 12 + 8) << "default scene, 2 x 6 family members twice (overtopping, internal erosion), "
                                      "8 Table 3.4 dams";
}

TEST(BreachExamples, ScaleFamilyPeaksRiseWithScale) {
  // Both breach modes; every member breaches (the clay's undrained strength, 0.3 psf as
  // published, is so low that its pipes collapse at once, even in the smallest dams).
  for (const char* family : {"scale_family", "scale_family_internal_erosion"}) {
    for (const char* material : {"silty_sand_SM", "clay_CL"}) {
      double last = 0.0;
      for (int s = 0; s <= 5; ++s) {
        const auto file = kExamples / family / (std::string(material) + "_scale" + std::to_string(s) + ".yaml");
        const Result r = run_file(file);
        EXPECT_GT(r.peak_outflow, last) << file;
        EXPECT_TRUE(r.failed()) << file;
        last = r.peak_outflow;
      }
    }
  }
}

}  // namespace
