#pragma once
// run.json: what ran, where, how long. Written by rank 0 at the end of a run (and again at
// each checkpoint, so a killed run still has one):
//   {"program", "version", "git_hash", "build_type", "compiler", "cxx_flags", "mpi_library",
//    "ranks", "threads_per_rank", "host", "command_line", "started_utc", "wall_time_s",
//    "phases": {name: {calls, min_s, mean_s, max_s}}, "status", ...extra}
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"
#include "core/run/phase_timers.hpp"

namespace suite {

class RunRecord {
 public:
  RunRecord(const mpi::Comm& comm, std::string program, std::vector<std::string> command_line);
  // Extra top-level fields (e.g. "scene", "restarted_from").
  nlohmann::json& extra() { return extra_; }
  nlohmann::json to_json(const PhaseTimers& timers, const std::string& status) const;  // COLLECTIVE
  // COLLECTIVE; rank 0 writes `path` atomically.
  void write(const std::filesystem::path& path, const PhaseTimers& timers, const std::string& status) const;
  double wall_seconds() const;

 private:
  mpi::Comm comm_;
  std::string program_;
  std::vector<std::string> command_line_;
  std::string started_utc_;
  std::chrono::steady_clock::time_point start_;
  nlohmann::json extra_ = nlohmann::json::object();
};

// summary.json: the scalar responses of a run that studies read without parsing logs.
//   {"peak_outflow": 812.5, ..., "units": {"peak_outflow": "m^3/s", ...}}
class Summary {
 public:
  void set(const std::string& key, double value, const std::string& unit = "");
  void set(const std::string& key, const std::string& value);
  void set(const std::string& key, bool value);
  // A string literal would otherwise convert to bool, not to std::string.
  void set(const std::string& key, const char* value) { set(key, std::string(value)); }
  const nlohmann::json& json() const { return json_; }
  // Not collective: call on one rank. Atomic write.
  void write(const std::filesystem::path& path) const;

 private:
  nlohmann::json json_ = {{"units", nlohmann::json::object()}};
};

// Pretty JSON written atomically (temp + fsync + rename). Not collective.
// This machine's name ("unknown" if it cannot be read).
std::string host_name();

void write_json_atomic(const std::filesystem::path& path, const nlohmann::json& j);

}  // namespace suite
