#include "core/cli/command_line.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "core/config/config.hpp"

namespace suite::cli {

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
  app.add_option("-o,--out", cl.out, "output folder (created)")->capture_default_str();
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    result.message = app.help();
    return result;
  } catch (const CLI::ParseError& e) {
    result.exit_code = 2;
    result.message = fmt::format("{}: {}; run '{} --help' for usage", spec.program, e.what(), spec.program);
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
  if (dakota.size() == 2)
    cl.dakota = std::make_pair(std::filesystem::path(dakota[0]), std::filesystem::path(dakota[1]));
  cl.argv.assign(argv, argv + argc);
  result.command_line = std::move(cl);
  return result;
}

}  // namespace suite::cli
