#include "core/run/run_record.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <ctime>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/mpi/collective_try.hpp"
#include "core/run/build_info.hpp"

namespace suite {

namespace {
std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", tm);
}
}  // namespace

std::string host_name() {
  char buf[256] = {0};
  if (gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

void write_json_atomic(const std::filesystem::path& path, const nlohmann::json& j) {
  io::write_file_atomic(path, j.dump(2) + "\n");
}

RunRecord::RunRecord(const mpi::Comm& comm, std::string program, std::vector<std::string> command_line)
    : comm_(comm),
      program_(std::move(program)),
      command_line_(std::move(command_line)),
      started_utc_(utc_now()),
      start_(std::chrono::steady_clock::now()) {}

double RunRecord::wall_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

nlohmann::json RunRecord::to_json(const PhaseTimers& timers, const std::string& status) const {
  const BuildInfo b = build_info();
  const char* threads = std::getenv("OMP_NUM_THREADS");
  // The process's largest resident set so far (Linux reports KiB).
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peak_rss = 1024.0 * static_cast<double>(usage.ru_maxrss);
  nlohmann::json j = {
      {"program", program_},
      {"version", b.version},
      {"git_hash", b.git_hash},
      {"build_type", b.build_type},
      {"compiler", b.compiler},
      {"cxx_flags", b.cxx_flags},
      {"mpi_library", b.mpi},
      {"ranks", comm_.size()},
      {"threads_per_rank", threads ? std::atoi(threads) : 1},
      {"host", host_name()},
      {"command_line", command_line_},
      {"started_utc", started_utc_},
      {"wall_time_s", comm_.max(wall_seconds())},
      {"phases", timers.reduce_to_json(comm_)},
      {"peak_resident_memory_bytes", {{"max_rank", comm_.max(peak_rss)}, {"all_ranks", comm_.sum(peak_rss)}}},
      {"status", status},
  };
  for (const auto& [k, v] : extra_.items()) j[k] = v;
  return j;
}

void RunRecord::write(const std::filesystem::path& path, const PhaseTimers& timers, const std::string& status) const {
  const nlohmann::json j = to_json(timers, status);
  mpi::collective_try(comm_, [&] {
    if (comm_.is_root()) write_json_atomic(path, j);
  });
}

void Summary::set(const std::string& key, double value, const std::string& unit) {
  if (key == "units") throw LibraryError("summary key 'units' is reserved");
  json_[key] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  if (!unit.empty()) json_["units"][key] = unit;
}

void Summary::set(const std::string& key, const std::string& value) {
  json_[key] = value;
}
void Summary::set(const std::string& key, bool value) {
  json_[key] = value;
}

void Summary::write(const std::filesystem::path& path) const {
  write_json_atomic(path, json_);
}

}  // namespace suite
