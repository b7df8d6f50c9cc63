// Strict YAML configuration: typed access, defaults, ranges, units, unknown keys, overrides,
// and the messages a user sees for each kind of mistake.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <fstream>

#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "tests/support/test_dirs.hpp"

using suite::InputError;
using suite::config::Config;
using suite::config::Range;
using suite::testing::input_error_of;

namespace {

const char* kScene = R"(name: overtopping
soil:
  cohesion: 5 kPa
  friction_angle: 30
  density: 1.8 g/cm^3
reservoir:
  level: 6.5 ft
  inflow: [[0 h, 0 cfs], [2 h, 1200 cfs]]
walls: slip
steps: 100
gravity: [0, -9.81]
)";

Config scene(std::vector<std::string> overrides = {}) {
  return Config::from_string(kScene, "scene.yaml", overrides);
}

TEST(Config, ReadsTypedValuesAndConvertsUnitsToTheRequestedOnes) {
  auto cfg = scene();
  auto root = cfg.root();
  EXPECT_EQ(root.get<std::string>("name"), "overtopping");
  auto soil = root.section("soil");
  EXPECT_DOUBLE_EQ(soil.quantity("cohesion", "Pa"), 5000.0);
  EXPECT_DOUBLE_EQ(soil.quantity("friction_angle", "deg"), 30.0);  // bare number: requested unit
  EXPECT_NEAR(soil.quantity("density", "kg/m^3"), 1800.0, 1e-9);
  auto res = root.section("reservoir");
  EXPECT_NEAR(res.quantity("level", "m"), 6.5 * 0.3048, 1e-15);
  auto table = res.table("inflow", {"s", "m^3/s"});
  ASSERT_EQ(table.size(), 2u);
  EXPECT_DOUBLE_EQ(table[1][0], 7200.0);
  EXPECT_NEAR(table[1][1], 1200 * 0.028316846592, 1e-12);
  EXPECT_EQ(root.choice("walls", {"slip", "sticky", "friction"}), "slip");
  EXPECT_EQ(root.get<long long>("steps"), 100);
  EXPECT_EQ(root.get<std::vector<double>>("gravity"), (std::vector<double>{0, -9.81}));
  EXPECT_NO_THROW(cfg.finish());
}

TEST(Config, UnknownKeyNamesFileLineKeyAndSuggestion) {
  auto cfg = Config::from_string("soil:\n  cohesion: 5\n  frction_angle: 30\n", "dam.yaml");
  auto soil = cfg.root().section("soil");
  soil.quantity("cohesion", "Pa");
  soil.quantity("friction_angle", "deg", 35.0);
  const std::string msg = input_error_of([&] { cfg.finish(); });
  EXPECT_NE(msg.find("dam.yaml:3:3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown key 'soil.frction_angle'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("did you mean 'friction_angle'?"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cohesion, friction_angle"), std::string::npos) << msg;  // what is valid
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line";
}

TEST(Config, UnknownTopLevelSectionIsAnError) {
  auto cfg = Config::from_string("soil: {cohesion: 1}\nsoill: {cohesion: 2}\n", "x.yaml");
  cfg.root().section("soil").quantity("cohesion", "Pa");
  const std::string msg = input_error_of([&] { cfg.finish(); });
  EXPECT_NE(msg.find("x.yaml:2:1: unknown key 'soill'; did you mean 'soil'?"), std::string::npos) << msg;
}

TEST(Config, OutOfRangeValueNamesTheRangeAndUnit) {
  auto cfg = Config::from_string("soil:\n  cohesion: -3 kPa\n", "s.yaml");
  const std::string msg =
      input_error_of([&] { cfg.root().section("soil").quantity("cohesion", "Pa", Range::at_least(0)); });
  EXPECT_NE(msg.find("s.yaml:2:13: key 'soil.cohesion' = '-3 kPa': must be >= 0 Pa"), std::string::npos) << msg;
}

TEST(Config, BareNumberOutOfRangeSaysWhichUnitItWasReadIn) {
  auto cfg = Config::from_string("soil:\n  friction_angle: 30\n", "s.yaml");
  const std::string msg = input_error_of(
      [&] { cfg.root().section("soil").quantity("friction_angle", "rad", Range::between(0, 1.4)); });
  EXPECT_NE(msg.find("must be in [0, 1.4] rad; '30' has no unit, so it was read in rad"), std::string::npos) << msg;
  EXPECT_NE(msg.find("e.g. '30 deg'"), std::string::npos) << msg;
  auto with_unit = Config::from_string("soil:\n  friction_angle: 95 deg\n", "s.yaml");
  const std::string plain = input_error_of(
      [&] { with_unit.root().section("soil").quantity("friction_angle", "rad", Range::between(0, 1.4)); });
  EXPECT_EQ(plain.find("has no unit"), std::string::npos) << plain;
}

TEST(Config, WrongUnitKindIsExplained) {
  auto cfg = Config::from_string("level: 3 s\n", "s.yaml");
  const std::string msg = input_error_of([&] { cfg.root().quantity("level", "m"); });
  EXPECT_NE(msg.find("key 'level' = '3 s'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(time) cannot be converted to 'm' (length)"), std::string::npos) << msg;
}

TEST(Config, NotANumberAndNotAnInteger) {
  auto cfg = Config::from_string("a: abc\nb: 2.5\nc: .nan\n", "v.yaml");
  EXPECT_NE(input_error_of([&] { cfg.root().get<double>("a"); }).find("v.yaml:1:4: key 'a' = 'abc': expected a number"),
            std::string::npos);
  EXPECT_NE(input_error_of([&] { cfg.root().get<long long>("b"); }).find("expected a whole number"), std::string::npos);
  EXPECT_NE(input_error_of([&] { cfg.root().get<double>("c"); }).find("expected a"), std::string::npos);
}

TEST(Config, MissingRequiredKeyNamesTheSection) {
  auto cfg = Config::from_string("soil:\n  density: 1800\n", "m.yaml");
  const std::string msg = input_error_of([&] { cfg.root().section("soil").quantity("cohesion", "Pa"); });
  EXPECT_NE(msg.find("missing required key 'soil.cohesion' (a value in Pa)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("m.yaml:2:3"), std::string::npos) << msg;
}

TEST(Config, MissingRequiredKeyPointsAtItsMisspelling) {
  auto cfg = Config::from_string("reservoir:\n  dpth: 0.6 m\n", "r.yaml");
  const std::string msg = input_error_of([&] { cfg.root().section("reservoir").quantity("depth", "m"); });
  EXPECT_NE(msg.find("r.yaml:2:3: unknown key 'reservoir.dpth'; did you mean 'depth'? (it is required: a value in m)"),
            std::string::npos)
      << msg;
}

TEST(Config, OptionalSectionsAreAbsentOrRead) {
  auto cfg = Config::from_string("petsc_off: 1\noutput: {every: 3}\n", "o.yaml");
  EXPECT_FALSE(cfg.root().optional_section("restart").has_value());
  EXPECT_EQ(cfg.root().optional_section("output")->get<long long>("every"), 3);
  cfg.root().get<long long>("petsc_off");
  EXPECT_NO_THROW(cfg.finish());
}

TEST(Config, ChoiceSuggestsTheClosestValidValue) {
  auto cfg = Config::from_string("walls: stiky\n", "c.yaml");
  const std::string msg = input_error_of([&] { cfg.root().choice("walls", {"slip", "sticky", "friction"}); });
  EXPECT_NE(msg.find("did you mean 'sticky'? It must be one of slip, sticky, friction"), std::string::npos) << msg;
}

TEST(Config, OverridesReplaceAndAddValuesAndAreNamedInErrors) {
  auto cfg = scene({"soil.cohesion=7 kPa", "steps=5", "output.every=10"});
  auto root = cfg.root();
  EXPECT_DOUBLE_EQ(root.section("soil").quantity("cohesion", "Pa"), 7000.0);
  EXPECT_EQ(root.get<long long>("steps"), 5);
  EXPECT_EQ(root.section("output").get<long long>("every"), 10);

  auto bad = Config::from_string("soil:\n  cohesion: 1\n", "s.yaml", {"soil.cohesoin=7"});
  bad.root().section("soil").quantity("cohesion", "Pa");
  const std::string msg = input_error_of([&] { bad.finish(); });
  EXPECT_NE(msg.find("command-line override 'soil.cohesoin=7': unknown key 'soil.cohesoin'; did you mean 'cohesion'?"),
            std::string::npos)
      << msg;
  const std::string range = input_error_of([&] { scene({"steps=-1"}).root().integer("steps", 1, 1, 1000); });
  EXPECT_NE(range.find("command-line override 'steps=-1'"), std::string::npos) << range;
}

TEST(Config, KeysInsideAMapValuedOverrideNameTheOverride) {
  auto cfg = Config::from_string("steps: 1\n", "m.yaml", {"output={every: 5, evry_s: 1}"});
  cfg.root().get<long long>("steps");
  cfg.root().section("output").get<long long>("every");
  const std::string msg = input_error_of([&] { cfg.finish(); });
  EXPECT_NE(msg.find("command-line override 'output={every: 5, evry_s: 1}': unknown key 'output.evry_s'"),
            std::string::npos)
      << msg;
}

TEST(Config, DefaultsOfAnAbsentSectionAppearInTheEffectiveConfiguration) {
  auto cfg = Config::from_string("steps: 1\n", "e.yaml");
  cfg.root().get<long long>("steps");
  EXPECT_EQ(cfg.root().section_or_empty("checkpoint").get<long long>("keep", 2), 2);
  EXPECT_NE(cfg.effective_yaml().find("checkpoint:\n  keep: 2"), std::string::npos) << cfg.effective_yaml();
  EXPECT_NO_THROW(cfg.finish());
}

TEST(Config, MalformedOverridesAreRejected) {
  EXPECT_NE(input_error_of([] { scene({"steps="}); }).find("has no value"), std::string::npos);
  EXPECT_NE(input_error_of([] { scene({"name.x=3"}); }).find("'name' holds a value, not a section"), std::string::npos);
  EXPECT_NE(input_error_of([] { scene({"a..b=3"}); }).find("empty part"), std::string::npos);
}

TEST(Config, OverrideIndexesIntoLists) {
  auto cfg = Config::from_string("inlets:\n  - {height: 1}\n  - {height: 2}\n", "l.yaml", {"inlets.1.height=5"});
  auto inlets = cfg.root().sections("inlets");
  EXPECT_EQ(inlets[1].get<double>("height"), 5.0);
  EXPECT_EQ(inlets[1].path(), "inlets[1]");
  EXPECT_NE(input_error_of([] { Config::from_string("l: [1]\n", "l.yaml", {"l.3=1"}); }).find("use an index 0..0"),
            std::string::npos);
}

TEST(Config, DefaultsAppearInTheEffectiveConfiguration) {
  auto cfg = Config::from_string("soil: {}\n", "d.yaml");
  auto soil = cfg.root().section("soil");
  EXPECT_DOUBLE_EQ(soil.quantity("cohesion", "Pa", 2500.0), 2500.0);
  EXPECT_EQ(cfg.root().get<std::string>("mode", "lumped"), "lumped");
  const std::string yaml = cfg.effective_yaml();
  EXPECT_NE(yaml.find("cohesion: 2500 Pa"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("mode: lumped"), std::string::npos) << yaml;
  // The effective file reads back to the same values.
  auto again = Config::from_string(yaml, "effective.yaml");
  EXPECT_DOUBLE_EQ(again.root().section("soil").quantity("cohesion", "Pa"), 2500.0);
}

TEST(Config, DuplicateKeysAreRejected) {
  const std::string msg = input_error_of([] { Config::from_string("a: 1\nb: 2\na: 3\n", "dup.yaml"); });
  EXPECT_NE(msg.find("dup.yaml:3:1: key 'a' appears twice (first on line 1)"), std::string::npos) << msg;
}

TEST(Config, SyntaxErrorsAndMissingFilesNameTheFile) {
  EXPECT_NE(input_error_of([] { Config::from_string("a: [1, 2\n", "bad.yaml"); }).find("bad.yaml:"), std::string::npos);
  const std::string msg = input_error_of([] { Config::from_file("/nonexistent/scene.yaml"); });
  EXPECT_NE(msg.find("cannot open configuration file '/nonexistent/scene.yaml': no such file"), std::string::npos)
      << msg;
  EXPECT_NE(input_error_of([] { Config::from_string("- 1\n- 2\n", "list.yaml"); }).find("must be a mapping"),
            std::string::npos);
}

TEST(Config, RawSubtreesAreNotChecked) {
  auto cfg = Config::from_string("petsc:\n  ksp_type: cg\n  ksp_rtol: 1e-10\n", "p.yaml");
  auto node = cfg.root().raw("petsc");
  EXPECT_EQ(node["ksp_type"].as<std::string>(), "cg");
  EXPECT_NO_THROW(cfg.finish());
}

TEST(Config, TableRowsOfWrongLengthAreNamed) {
  auto cfg = Config::from_string("q: [[0, 1], [1]]\n", "t.yaml");
  const std::string msg = input_error_of([&] { cfg.root().table("q", {"s", "m^3/s"}); });
  EXPECT_NE(msg.find("row 2 ('[1]') must have 2 entries [s, m^3/s]"), std::string::npos) << msg;
}

TEST(Config, FromFileReportsItsPath) {
  const auto path = std::filesystem::temp_directory_path() / "suite_config_from_file.yaml";
  std::ofstream(path) << "x: 1\nyy: 2\n";
  auto cfg = Config::from_file(path);
  cfg.root().get<double>("x");
  cfg.root().has("y");
  const std::string msg = input_error_of([&] { cfg.finish(); });
  EXPECT_NE(msg.find(path.string() + ":2:1: unknown key 'yy'; did you mean 'y'?"), std::string::npos) << msg;
  std::filesystem::remove(path);
}

}  // namespace
