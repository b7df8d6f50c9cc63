#pragma once
// The command line of the suite's tools with subcommands (seedcarve, study):
//
//   <program> COMMAND [TARGET ...] [key.path=value ...] [--option VALUE ...] [--log-level LEVEL]
//
// Each command declares its options and how many targets (files, folders) it takes, so that
// `<program> COMMAND --help` describes that command, an option another command owns is refused
// instead of ignored, and numbers are checked before any work starts. Parsed with CLI11 in
// command_line.cpp (the one file that includes it). Pure: prints nothing, never exits.
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>


namespace suite::cli {

struct OptionSpec {
  enum class Kind {
    text,      // one string
    number,    // one finite real number
    count,     // one whole number >= `least`
    flag,      // present or not
    repeated,  // a string, given any number of times
  };
  std::string name;  // long name without the dashes, e.g. "out"
  Kind kind = Kind::text;
  std::string help;
  std::string value_name;  // for the help, e.g. "DIR"
  bool required = false;
  long least = 0;  // count: the smallest value accepted

  static OptionSpec text(std::string name, std::string value_name, std::string help, bool required = false) {
    return {std::move(name), Kind::text, std::move(help), std::move(value_name), required, 0};
  }
  static OptionSpec number(std::string name, std::string value_name, std::string help) {
    return {std::move(name), Kind::number, std::move(help), std::move(value_name), false, 0};
  }
  static OptionSpec count(std::string name, std::string value_name, std::string help, long least) {
    return {std::move(name), Kind::count, std::move(help), std::move(value_name), false, least};
  }
  static OptionSpec flag(std::string name, std::string help) {
    return {std::move(name), Kind::flag, std::move(help), "", false, 0};
  }
  static OptionSpec repeated(std::string name, std::string value_name, std::string help, bool required = false) {
    return {std::move(name), Kind::repeated, std::move(help), std::move(value_name), required, 0};
  }
};

struct CommandSpec {
  std::string name;
  std::string help;     // one paragraph for `<program> --help` and `<program> COMMAND --help`
  std::string targets;  // for the help, e.g. "IMAGES..."; empty: the command takes none
  int min_targets = 0;
  int max_targets = 0;     // -1: any number
  bool overrides = false;  // accepts key.path=value overrides
  std::vector<OptionSpec> options;
};

struct ProgramSpec {
  std::string program;
  std::string description;
  std::vector<CommandSpec> commands;
};

struct CommandArguments {
  std::string command;
  std::vector<std::string> targets;
  std::vector<std::string> overrides;  // "key.path=value", in order
  std::map<std::string, std::string> text;
  std::map<std::string, double> numbers;
  std::map<std::string, long> counts;
  std::map<std::string, std::vector<std::string>> repeated;
  std::vector<std::string> flags;  // names of the flags given
  std::string log_level = "info";

  bool has(const std::string& name) const;
  // The text of an option, or `fallback` when it was not given.
  std::string text_or(const std::string& name, const std::string& fallback) const;
  std::optional<double> number(const std::string& name) const;
  long count_or(const std::string& name, long fallback) const;
  std::vector<std::string> all(const std::string& name) const;
};

struct ParsedCommand {
  std::optional<CommandArguments> arguments;  // empty when the program should exit now
  int exit_code = 0;                          // 0 after --help, 2 after a usage error
  std::string message;                        // help text or the error, for rank 0 to print
};

ParsedCommand parse_command(const ProgramSpec& spec, int argc, const char* const* argv);

}  // namespace suite::cli
