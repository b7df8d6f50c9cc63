#pragma once
// Runs one external program for a study evaluation: in its work directory, with its standard
// output and error captured to files there, in its own process group so a timeout kills the
// program and everything it started.
#include <filesystem>
#include <string>
#include <vector>

namespace suite::studies {

struct ProcessResult {
  bool started = false;  // false: could not fork or exec (the reason says why)
  bool timed_out = false;
  int exit_status = -1;  // the program's exit code, or 128 + signal
  double wall_s = 0.0;
  std::string reason;  // "" on exit status 0
};

// argv[0] is looked up on PATH when it has no '/'. time_limit_s <= 0: no limit.
ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& work_dir,
                          double time_limit_s);

}  // namespace suite::studies
