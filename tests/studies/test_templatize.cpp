// `study templatize`: a template made from an existing input file renders back to that file
// when given the numbers it replaced (fixed-column text and YAML with flow mappings), and
// places that hold no number are refused with the place named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "studies/template/template.hpp"
#include "studies/template/templatize.hpp"
#include "tests/support/test_dirs.hpp"

namespace {

using namespace suite::studies;
using suite::testing::input_error_of;

// A fixed-column input in the style of the dissertation's WinDAM C files.
const std::string kWinDam =
    "TITLE synthetic dam {scale 3}\n"
    "IEMODEL 2 120    300 70 0.2\n"
    "CRESTPRFL\n"
    "0     32.0\n"
    "900   32.0\n";

TEST(Templatize, FixedColumnsRoundTrip) {
  const auto t = templatize(kWinDam, "dam.wdc", {{"Kd", "2:4"}, {"Us", "2:5"}, {"H1", "4:2"}, {"H2", "5:2"}});
  EXPECT_EQ(t.text,
            "TITLE synthetic dam \\{scale 3\\}\n"
            "IEMODEL 2 120    {Kd} {Us} 0.2\n"
            "CRESTPRFL\n"
            "0     {H1}\n"
            "900   {H2}\n");
  EXPECT_EQ(t.values.at("Kd"), 300.0);
  EXPECT_EQ(t.values.at("H2"), 32.0);
  // Rendering with the values found gives the file back, up to the numbers' %.10g form.
  std::string expected = kWinDam;
  for (auto at = expected.find("32.0"); at != std::string::npos; at = expected.find("32.0"))
    expected.replace(at, 4, "32");
  EXPECT_EQ(Template::parse(t.text, "dam.tmpl").render(t.values), expected);
}

TEST(Templatize, YamlKeysRoundTrip) {
  const std::string yaml =
      "dam: {height: 12 m, crest_width: 6 m}\n"
      "soil:\n  erodibility: 20 (ft/h)/psf\n  critical_shear_stress: 0.1 psf\n"
      "inflow:\n  table: [[0 h, 0 cfs], [2 h, 1200 cfs]]\n";
  const auto t = templatize(yaml, "dam.yaml", {{"H", "dam.height"}, {"Kd", "soil.erodibility"}});
  EXPECT_EQ(t.text,
            "dam: \\{height: {H} m, crest_width: 6 m\\}\n"
            "soil:\n  erodibility: {Kd} (ft/h)/psf\n  critical_shear_stress: 0.1 psf\n"
            "inflow:\n  table: [[0 h, 0 cfs], [2 h, 1200 cfs]]\n");
  EXPECT_EQ(Template::parse(t.text, "dam.tmpl").render(t.values), yaml);
  EXPECT_EQ(Template::parse(t.text, "dam.tmpl").render({{"H", 24}, {"Kd", 300}}).find("height: 24 m"), 6u);
}

TEST(Templatize, PlacesWithoutANumberAreRefused) {
  auto has = [](const std::string& msg, const std::string& part) {
    EXPECT_NE(msg.find(part), std::string::npos) << "'" << part << "' not in: " << msg;
  };
  has(input_error_of([&] {
        templatize(kWinDam, "dam.wdc", {{"X", "1:2"}});
      }),
      "dam.wdc:1: variable X: field 2 is 'synthetic', not a number");
  has(input_error_of([&] { templatize(kWinDam, "dam.wdc", {{"X", "9:1"}}); }), "there is no line 9");
  has(input_error_of([&] {
        templatize("a:\n  b: text\n", "s.yaml", {{"X", "a.b"}});
      }),
      "s.yaml:2:6: variable X: 'text' does not start with a number");
  has(input_error_of([&] { templatize("a: 1\n", "s.yaml", {{"X", "a.c"}}); }), "there is no key 'a.c'");
  has(input_error_of([&] { templatize(kWinDam, "dam.wdc", {{"X", "2:4"}, {"Y", "2:4"}}); }), "name the same number");
}

}  // namespace

// The shipped mpm2grid study's template (studies/examples/mpm2grid/) is still the scene it was
// made from: given the scene's own cohesion and reservoir level it renders to the scene file
// byte for byte, so a change to the scene that the template missed fails here.
TEST(Templatize, ShippedMpm2gridTemplateRendersToItsScene) {
  const std::filesystem::path src = SUITE_SOURCE_DIR;
  const auto read = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    EXPECT_TRUE(in) << p;
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const auto scene = read(src / "solvers/mpm2grid/scenes/table_3_4_example2.yaml");
  const auto tmpl = Template::parse(read(src / "studies/examples/mpm2grid/table_3_4_example2.tmpl"), "table_3_4_example2.tmpl");
  EXPECT_EQ(tmpl.names(), (std::vector<std::string>{"c0", "level"}));
  EXPECT_EQ(tmpl.render({{"c0", 4935}, {"level", 3.25}}), scene);
}
