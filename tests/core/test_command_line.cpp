#include <gtest/gtest.h>

#include "core/cli/command_line.hpp"

namespace {

suite::cli::Parsed parse(std::vector<const char*> args, bool scene_required = true) {
  args.insert(args.begin(), "mpm2grid");
  return suite::cli::parse({"mpm2grid", "test program", scene_required, "out"}, static_cast<int>(args.size()),
                           args.data());
}

TEST(CommandLine, SceneThenOverridesThenOptions) {
  auto p = parse({"dam.yaml", "soil.cohesion=5kPa", "steps=10", "--out", "run1", "--restart", "latest"});
  ASSERT_TRUE(p.command_line);
  EXPECT_EQ(p.command_line->scene->string(), "dam.yaml");
  EXPECT_EQ(p.command_line->overrides, (std::vector<std::string>{"soil.cohesion=5kPa", "steps=10"}));
  EXPECT_EQ(p.command_line->out.string(), "run1");
  EXPECT_TRUE(p.command_line->out_given);
  EXPECT_FALSE(parse({"dam.yaml"}).command_line->out_given) << "the default folder is not given";
  EXPECT_EQ(p.command_line->restart.value_or(""), "latest");
  EXPECT_EQ(p.command_line->argv.size(), 8u);
}

TEST(CommandLine, UsageErrorsAreOneLineWithStatusTwo) {
  auto none = parse({});
  EXPECT_FALSE(none.command_line);
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.message.find("no scene file given"), std::string::npos);
  auto two = parse({"a.yaml", "b.yaml"});
  EXPECT_NE(two.message.find("unexpected argument 'b.yaml'"), std::string::npos);
  auto level = parse({"a.yaml", "--log-level", "loud"});
  EXPECT_EQ(level.exit_code, 2);
  EXPECT_TRUE(parse({}, false).command_line.has_value()) << "embedded default scene";
}

TEST(CommandLine, HelpIsReturnedNotPrinted) {
  auto h = parse({"--help"});
  EXPECT_FALSE(h.command_line);
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.message.find("--restart"), std::string::npos);
}

}  // namespace
