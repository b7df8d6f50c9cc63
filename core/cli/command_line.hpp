#pragma once
// The command line shared by the suite's solver executables:
//
//   <program> [scene.yaml] [key.path=value ...] [--out DIR] [--restart FILE|latest]
//             [--log-level LEVEL] [--log-all-ranks] [--dakota PARAMS RESULTS]
//
// CLI11 lives in command_line.cpp only (it is header-only and slow to compile).
// PETSc options go in the scene's `petsc_options` key or the PETSC_OPTIONS environment variable.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace suite::cli {

struct Spec {
  std::string program;
  std::string description;
  bool scene_required = true;  // false: an embedded default scene is used without one
  std::string default_out = "output";
  bool dakota_driver = false;  // offer --dakota PARAMS RESULTS
};

struct CommandLine {
  std::optional<std::filesystem::path> scene;
  std::vector<std::string> overrides;  // "key.path=value", in order
  std::filesystem::path out;
  bool out_given = false;              // --out was on the command line (not the default)
  std::optional<std::string> restart;  // a checkpoint file, or "latest"
  // --dakota PARAMS RESULTS: run as a Dakota analysis driver (read the parameters file, write
  // the results file); for executables that support it.
  std::optional<std::pair<std::filesystem::path, std::filesystem::path>> dakota;
  std::string log_level = "info";
  bool log_all_ranks = false;
  std::vector<std::string> argv;  // the whole command line, for run.json
};

struct Parsed {
  std::optional<CommandLine> command_line;  // empty when the program should exit now
  int exit_code = 0;                        // 0 after --help, 2 after a usage error
  std::string message;                      // help text or the error, for rank 0 to print
};

// Pure: prints nothing, never exits.
Parsed parse(const Spec& spec, int argc, const char* const* argv);

}  // namespace suite::cli
