#include "core/cli/command_line.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <deque>
#include <tuple>

#include "core/cli/subcommands.hpp"
#include "core/config/config.hpp"

namespace suite::cli {
namespace {

// Runs CLI11 on the command line. On --help (exit 0, the help of the command asked about) or a
// usage error (exit 2, one line that points to that command's --help) returns the exit status
// and the message for rank 0; nothing when the program should go on.
std::optional<std::pair<int, std::string>> stop_after_parse(CLI::App& app, const std::string& program, int argc,
                                                            const char* const* argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    return std::make_pair(0, app.help());
  } catch (const CLI::ParseError& e) {
    const auto chosen = app.get_subcommands();
    return std::make_pair(2, fmt::format("{}: {}; run '{}{} --help' for usage", program, e.what(), program,
                                         chosen.empty() ? "" : " " + chosen.front()->get_name()));
  }
  return std::nullopt;
}

}  // namespace

Parsed parse(const Spec& spec, int argc, const char* const* argv) {
  CLI::App app(spec.description, spec.program);
  std::vector<std::string> positional;
  CommandLine cl;
  cl.out = spec.default_out;
  std::string restart;
  app.add_option("args", positional,
                 spec.scene_required
                     ? "scene YAML file, then key.path=value overrides"
                     : "scene YAML file (default: the embedded demo scene), then key.path=value overrides");
  CLI::Option* out = app.add_option("-o,--out", cl.out, "output folder (created)")->capture_default_str();
  app.add_option("--restart", restart, "continue from a checkpoint file, or 'latest' in the output folder");
  app.add_option("--log-level", cl.log_level, "debug, info, warn, error or off")
      ->check(CLI::IsMember({"debug", "info", "warn", "error", "off"}))
      ->capture_default_str();
  app.add_flag("--log-all-ranks", cl.log_all_ranks, "print info messages from every rank, not only rank 0");
  std::vector<std::string> dakota;
  if (spec.dakota_driver)
    app.add_option("--dakota", dakota,
                   "run as a Dakota analysis driver: read the parameters file PARAMS (variables named by scene "
                   "keys), write the results file RESULTS (responses named by summary keys)")
        ->expected(2);
  app.footer(
      "Overrides set any key of the scene, e.g. soil.cohesion=5kPa output.every=20.\n"
      "PETSc options (mpm2grid, drag: consistent): the scene's petsc_options key or the PETSC_OPTIONS environment "
      "variable.");

  Parsed result;
  if (auto stop = stop_after_parse(app, spec.program, argc, argv)) {
    std::tie(result.exit_code, result.message) = std::move(*stop);
    return result;
  }
  for (const auto& arg : positional) {
    if (config::looks_like_override(arg)) {
      cl.overrides.push_back(arg);
    } else if (!cl.scene) {
      cl.scene = arg;
    } else {
      result.exit_code = 2;
      result.message =
          fmt::format("{}: unexpected argument '{}' after the scene '{}'; overrides are written key.path=value",
                      spec.program, arg, cl.scene->string());
      return result;
    }
  }
  if (spec.scene_required && !cl.scene) {
    result.exit_code = 2;
    result.message =
        fmt::format("{}: no scene file given; usage: {} scene.yaml [key.path=value ...]", spec.program, spec.program);
    return result;
  }
  if (!restart.empty()) cl.restart = restart;
  cl.out_given = out->count() > 0;
  if (dakota.size() == 2)
    cl.dakota = std::make_pair(std::filesystem::path(dakota[0]), std::filesystem::path(dakota[1]));
  cl.argv.assign(argv, argv + argc);
  result.command_line = std::move(cl);
  return result;
}

namespace {

const char* const kLogLevels[] = {"debug", "info", "warn", "error", "off"};

// A whole or real number that is all of `text` (no trailing characters, finite).
std::optional<double> read_number(const std::string& text) {
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

}  // namespace

bool CommandArguments::has(const std::string& name) const {
  return text.count(name) || numbers.count(name) || counts.count(name) || repeated.count(name) ||
         std::find(flags.begin(), flags.end(), name) != flags.end();
}

std::string CommandArguments::text_or(const std::string& name, const std::string& fallback) const {
  const auto it = text.find(name);
  return it == text.end() ? fallback : it->second;
}

std::optional<double> CommandArguments::number(const std::string& name) const {
  const auto it = numbers.find(name);
  return it == numbers.end() ? std::nullopt : std::optional<double>(it->second);
}

long CommandArguments::count_or(const std::string& name, long fallback) const {
  const auto it = counts.find(name);
  return it == counts.end() ? fallback : it->second;
}

std::vector<std::string> CommandArguments::all(const std::string& name) const {
  const auto it = repeated.find(name);
  return it == repeated.end() ? std::vector<std::string>{} : it->second;
}

ParsedCommand parse_command(const ProgramSpec& spec, int argc, const char* const* argv) {
  CLI::App app(spec.description, spec.program);
  app.require_subcommand(1);
  app.footer(fmt::format("'{} COMMAND --help' describes one command.", spec.program));
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "debug, info, warn, error or off")
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(kLogLevels), std::end(kLogLevels))))
      ->capture_default_str();
  // Storage the parser writes into, per command and option (a deque keeps the addresses).
  struct Slot {
    const CommandSpec* command = nullptr;
    const OptionSpec* option = nullptr;
    std::string value;
    std::vector<std::string> values;
    bool set = false;
  };
  std::deque<Slot> slots;
  std::map<std::string, std::vector<std::string>> positional;
  std::map<std::string, CLI::App*> apps;
  for (const auto& command : spec.commands) {
    CLI::App* sub = app.add_subcommand(command.name, command.help);
    sub->fallthrough();  // --log-level after the command
    apps[command.name] = sub;
    std::string what = command.targets;
    if (command.overrides) what += what.empty() ? "key.path=value overrides" : ", then key.path=value overrides";
    if (!what.empty()) sub->add_option("args", positional[command.name], what);
    for (const auto& o : command.options) {
      Slot& slot = slots.emplace_back();
      slot.command = &command;
      slot.option = &o;
      CLI::Option* opt = nullptr;
      const std::string flag = "--" + o.name;
      switch (o.kind) {
        case OptionSpec::Kind::flag:
          opt = sub->add_flag(flag, slot.set, o.help);
          break;
        case OptionSpec::Kind::repeated:
          opt = sub->add_option(flag, slot.values, o.help)
                    ->expected(1)
                    ->allow_extra_args(false)
                    ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
          break;
        default:
          opt = sub->add_option(flag, slot.value, o.help);
          break;
      }
      if (!o.value_name.empty() && o.kind != OptionSpec::Kind::flag) opt->type_name(o.value_name);
      if (o.required) opt->required();
    }
  }

  ParsedCommand result;
  std::vector<std::string> names;
  for (const auto& command : spec.commands) names.push_back(command.name);
  const std::string first = argc > 1 ? argv[1] : "";
  if (first.empty() || (first[0] != '-' && std::find(names.begin(), names.end(), first) == names.end())) {
    result.exit_code = 2;
    result.message = fmt::format("{}: {}; the commands are {}; run '{} --help' for usage", spec.program,
                                 first.empty() ? "no command given" : fmt::format("unknown command '{}'", first),
                                 fmt::format("{}", fmt::join(names, ", ")), spec.program);
    return result;
  }
  const auto usage_error = [&](const std::string& what, const std::string& command) {
    result.exit_code = 2;
    result.message = fmt::format("{}: {}; run '{}{} --help' for usage", spec.program, what, spec.program,
                                 command.empty() ? "" : " " + command);
    return result;
  };
  if (auto stop = stop_after_parse(app, spec.program, argc, argv)) {
    std::tie(result.exit_code, result.message) = std::move(*stop);
    return result;
  }

  CommandArguments a;
  a.command = app.get_subcommands().front()->get_name();
  a.log_level = log_level;
  const CommandSpec& command =
      *std::find_if(spec.commands.begin(), spec.commands.end(), [&](const auto& c) { return c.name == a.command; });
  for (const auto& arg : positional[command.name]) {
    if (config::looks_like_override(arg)) {
      if (!command.overrides)
        return usage_error(
            fmt::format("'{} {}' takes no key.path=value overrides (got '{}')", spec.program, command.name, arg),
            command.name);
      a.overrides.push_back(arg);
    } else {
      a.targets.push_back(arg);
    }
  }
  const int n = static_cast<int>(a.targets.size());
  if (n < command.min_targets || (command.max_targets >= 0 && n > command.max_targets)) {
    const std::string want = command.min_targets == command.max_targets ? fmt::format("{}", command.min_targets)
                             : command.max_targets < 0
                                 ? fmt::format("at least {}", command.min_targets)
                                 : fmt::format("{} to {}", command.min_targets, command.max_targets);
    return usage_error(fmt::format("'{} {}' takes {} argument{} ({}), got {}{}", spec.program, command.name, want,
                                   command.max_targets == 1 ? "" : "s", command.targets, n,
                                   n ? fmt::format(": '{}'", fmt::join(a.targets, "' '")) : ""),
                       command.name);
  }
  for (const auto& slot : slots) {
    if (slot.command != &command) continue;
    const OptionSpec& o = *slot.option;
    CLI::Option* given = apps[command.name]->get_option("--" + o.name);
    if (!given || given->count() == 0) continue;
    switch (o.kind) {
      case OptionSpec::Kind::flag:
        a.flags.push_back(o.name);
        break;
      case OptionSpec::Kind::repeated:
        a.repeated[o.name] = slot.values;
        break;
      case OptionSpec::Kind::text:
        a.text[o.name] = slot.value;
        break;
      case OptionSpec::Kind::number: {
        const auto x = read_number(slot.value);
        if (!x) return usage_error(fmt::format("--{} '{}': give a number", o.name, slot.value), command.name);
        a.numbers[o.name] = *x;
        break;
      }
      case OptionSpec::Kind::count: {
        const auto x = read_number(slot.value);
        if (!x || *x != std::floor(*x) || *x < static_cast<double>(o.least) || *x > 1e15)
          return usage_error(fmt::format("--{} '{}': give a whole number of at least {}", o.name, slot.value, o.least),
                             command.name);
        a.counts[o.name] = static_cast<long>(*x);
        break;
      }
    }
  }
  result.arguments = std::move(a);
  return result;
}

}  // namespace suite::cli
