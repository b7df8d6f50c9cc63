// The scene a restart compares: Config::resolved() records every key as the program read it
// (units converted, defaults included), and SceneRecord names each key that differs.
#include <gtest/gtest.h>

#include <fstream>

#include "core/checkpoint/scene_match.hpp"
#include "core/config/config.hpp"
#include "core/errors.hpp"
#include "tests/support/test_dirs.hpp"

using suite::InputError;
using suite::checkpoint::SceneRecord;
using suite::config::Config;
using suite::config::Range;
using suite::testing::input_error_of;

namespace {

// Reads the keys a small solver would: quantities, a default, a list of sections, a choice.
SceneRecord read(const std::string& text, const std::vector<std::string>& overrides = {}) {
  const auto cfg = Config::from_string(text, "scene.yaml", overrides);
  const auto root = cfg.root();
  root.section("soil").quantity("young", "Pa", Range::positive());
  root.section("soil").quantity("friction_angle", "rad", 0.5, Range::positive());
  for (const auto& r : root.sections("regions")) r.quantity("height", "m");
  root.choice("drag", {"lumped", "consistent"}, "lumped");
  const auto time = root.section("time");
  time.quantity("end", "s", Range::positive());
  time.integer("max_steps", 0, 0, 1000000);
  cfg.finish();
  return SceneRecord(cfg);
}

const char* kScene = "soil: {young: 20 MPa}\nregions: [{height: 3.75 m}]\ntime: {end: 10 s}\n";

TEST(SceneRecord, SameMeaningReadsTheSameWhateverTheUnits) {
  const auto a = read(kScene);
  const auto b = read(
      "soil: {young: 20000 kPa, friction_angle: 0.5}\nregions: [{height: 375 cm}]\n"
      "time: {end: 10000 ms}\ndrag: lumped\n");
  EXPECT_TRUE(a.differences(b, {}).empty()) << a.text() << "\n---\n" << b.text();
  EXPECT_EQ(a.keys().at("soil.young"), "20000000 Pa");
  EXPECT_EQ(a.keys().at("regions[0].height"), "3.75 m");
  EXPECT_EQ(a.keys().at("drag"), "lumped") << "a default is part of the scene";
}

TEST(SceneRecord, NamesEveryKeyThatDiffersExceptThoseThatMayChange) {
  const auto saved = read(kScene);
  const auto now =
      read(kScene, {"regions.0.height=3 m", "soil.friction_angle=0.6", "time.end=20 s", "time.max_steps=5"});
  EXPECT_EQ(saved.differences(now, {}),
            (std::vector<std::string>{"regions[0].height", "soil.friction_angle", "time.end", "time.max_steps"}));
  // An entry covers its key and every key below it, not a key that merely starts the same.
  EXPECT_EQ(saved.differences(now, {"time", "soil.friction"}),
            (std::vector<std::string>{"regions[0].height", "soil.friction_angle"}));
  const auto msg = input_error_of([&] { saved.require_same(now, {"time"}, "checkpoint 'c.h5'"); });
  EXPECT_NE(msg.find("checkpoint 'c.h5' was written for another scene"), std::string::npos) << msg;
  EXPECT_NE(msg.find("regions[0].height: '3.75 m' there, '3 m' here"), std::string::npos) << msg;
  EXPECT_NE(msg.find("a restart may change only time"), std::string::npos) << msg;
  EXPECT_NO_THROW(saved.require_same(read(kScene, {"time.end=20 s"}), {"time"}, "c"));
}

TEST(SceneRecord, KeysOnlyOneSideHasCount) {
  const auto saved = read(kScene);
  const auto now = read("soil: {young: 20 MPa}\nregions: [{height: 3.75 m}, {height: 1 m}]\ntime: {end: 10 s}\n");
  EXPECT_EQ(saved.differences(now, {}), (std::vector<std::string>{"regions[1].height"}));
  const auto msg = input_error_of([&] { saved.require_same(now, {}, "c"); });
  EXPECT_NE(msg.find("regions[1].height: not set there, '1 m' here"), std::string::npos) << msg;
}

TEST(SceneRecord, TextRoundTripsAndDamageIsReported) {
  const auto a = read(kScene, {"soil.young=353.7 kPa"});
  const auto b = SceneRecord::from_bytes(a.bytes(), "x");
  EXPECT_EQ(a.keys(), b.keys());
  EXPECT_EQ(b.keys().at("soil.young"), "353700 Pa");
  EXPECT_THROW(SceneRecord::from_text("soil.young 3\n", "x"), InputError);
}

// A file's content is part of the scene, its place is not.
TEST(SceneRecord, FilesCountByContent) {
  suite::mpi::Comm self(MPI_COMM_SELF);
  const auto dir = suite::testing::scratch_dir(self);
  std::ofstream(dir / "a.csv") << "0,1\n";
  std::ofstream(dir / "b.csv") << "0,1\n";
  std::ofstream(dir / "c.csv") << "0,2\n";
  const auto with = [&](const char* name) {
    const auto cfg = Config::from_string(std::string("inflow: ") + (dir / name).string() + "\n", "s.yaml");
    cfg.root().file("inflow");
    return SceneRecord(cfg);
  };
  EXPECT_TRUE(with("a.csv").differences(with("b.csv"), {}).empty());
  EXPECT_EQ(with("a.csv").differences(with("c.csv"), {}), std::vector<std::string>{"inflow"});
}

}  // namespace
