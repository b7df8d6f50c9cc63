// The subcommand command line of seedcarve and study (core/cli/subcommands.hpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/cli/subcommands.hpp"

namespace {

using suite::cli::CommandSpec;
using suite::cli::OptionSpec;

suite::cli::ProgramSpec spec() {
  return {"tool",
          "a test tool",
          {CommandSpec{"carve",
                       "carve one file",
                       "FILE",
                       1,
                       1,
                       false,
                       {OptionSpec::count("resolution", "N", "voxels per side", 1),
                        OptionSpec::number("weight", "MG", "weight")}},
           CommandSpec{"measure",
                       "measure images",
                       "IMAGES...",
                       1,
                       -1,
                       true,
                       {OptionSpec::text("profile", "P", "profile", true), OptionSpec::text("out", "DIR", "folder"),
                        OptionSpec::flag("retry-failed", "again"), OptionSpec::repeated("var", "N=L", "variable")}}}};
}

suite::cli::ParsedCommand parse(std::vector<std::string> args) {
  args.insert(args.begin(), "tool");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  return suite::cli::parse_command(spec(), static_cast<int>(argv.size()), argv.data());
}

bool says(const suite::cli::ParsedCommand& p, const std::string& text) {
  return p.message.find(text) != std::string::npos;
}

TEST(Subcommands, TargetsOverridesAndOptionsOfTheCommand) {
  const auto p = parse({"measure", "a.png", "b.png", "camera.step=10deg", "--profile", "p.yaml", "--var", "k=1",
                        "--var", "c=2", "--retry-failed", "--log-level", "debug"});
  ASSERT_TRUE(p.arguments) << p.message;
  const auto& a = *p.arguments;
  EXPECT_EQ(a.command, "measure");
  EXPECT_EQ(a.targets, (std::vector<std::string>{"a.png", "b.png"}));
  EXPECT_EQ(a.overrides, (std::vector<std::string>{"camera.step=10deg"}));
  EXPECT_EQ(a.text_or("profile", ""), "p.yaml");
  EXPECT_EQ(a.text_or("out", "default"), "default");
  EXPECT_EQ(a.all("var"), (std::vector<std::string>{"k=1", "c=2"}));
  EXPECT_TRUE(a.has("retry-failed"));
  EXPECT_EQ(a.log_level, "debug");
}

TEST(Subcommands, HelpOfOneCommandDescribesItsOptions) {
  const auto h = parse({"carve", "--help"});
  EXPECT_FALSE(h.arguments);
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_TRUE(says(h, "--resolution")) << h.message;
  EXPECT_FALSE(says(h, "--profile")) << "another command's option";
  const auto top = parse({"--help"});
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_TRUE(says(top, "carve") && says(top, "measure")) << top.message;
}

TEST(Subcommands, NumbersAreCheckedBeforeAnyWork) {
  EXPECT_EQ(parse({"carve", "f.dat", "--resolution", "64"}).arguments->count_or("resolution", 0), 64);
  for (const char* bad : {"-5", "0", "100.7", "many", "1e99"}) {
    const auto p = parse({"carve", "f.dat", "--resolution", bad});
    EXPECT_FALSE(p.arguments) << bad;
    EXPECT_EQ(p.exit_code, 2) << bad;
    EXPECT_TRUE(says(p, "--resolution")) << p.message;
  }
  EXPECT_DOUBLE_EQ(*parse({"carve", "f.dat", "--weight", "12.5"}).arguments->number("weight"), 12.5);
  EXPECT_TRUE(says(parse({"carve", "f.dat", "--weight", "12mg"}), "give a number"));
}

TEST(Subcommands, WhatACommandDoesNotTakeIsRefusedNotIgnored) {
  EXPECT_TRUE(says(parse({"carve", "f.dat", "--out", "x"}), "--out"));
  EXPECT_TRUE(says(parse({"carve", "f.dat", "soil.e=1"}), "takes no key.path=value overrides"));
  EXPECT_TRUE(says(parse({"carve", "a.dat", "b.dat"}), "takes 1 argument (FILE), got 2"));
  EXPECT_TRUE(says(parse({"carve"}), "got 0"));
  EXPECT_TRUE(says(parse({"measure", "a.png"}), "--profile is required"));
  const auto unknown = parse({"carv", "f.dat"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(says(unknown, "unknown command 'carv'") && says(unknown, "carve, measure")) << unknown.message;
  EXPECT_TRUE(says(parse({}), "no command given"));
}

}  // namespace
