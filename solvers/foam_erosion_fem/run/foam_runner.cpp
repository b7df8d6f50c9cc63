#include "solvers/foam_erosion_fem/run/foam_runner.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <thread>

#include "core/errors.hpp"

extern char** environ;

namespace suite::foam_erosion {

namespace fs = std::filesystem;

namespace {

// The environment for a child: ours without the MPI launcher's variables (a child mpirun must
// not think it is a rank of our job), with WM_PROJECT_DIR set. The user's own OMPI_MCA_ settings
// stay; the ones MPI_Init of this process set for itself (ess=singleton, orte_*, pmix) go, or
// a child mpirun fails at once without a word.
std::vector<std::string> child_environment(const fs::path& project_dir) {
  const auto starts = [](const std::string& kv, const char* prefix) { return kv.rfind(prefix, 0) == 0; };
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string kv(*e);
    const bool launcher_mca = starts(kv, "OMPI_MCA_ess") || starts(kv, "OMPI_MCA_orte_") || starts(kv, "OMPI_MCA_pmix");
    const bool user_mca = starts(kv, "OMPI_MCA_") && !launcher_mca;
    const bool mpi_internal = (starts(kv, "OMPI_") || starts(kv, "PMIX_") || starts(kv, "OPAL_") || starts(kv, "PMI_")) &&
                              !starts(kv, "OMPI_ALLOW_RUN_AS_ROOT") && !user_mca;
    if (mpi_internal || starts(kv, "WM_PROJECT_DIR=")) continue;
    env.push_back(kv);
  }
  env.push_back("WM_PROJECT_DIR=" + project_dir.string());
  return env;
}

std::vector<char*> c_strings(std::vector<std::string>& v) {
  std::vector<char*> out;
  for (auto& s : v) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

// Follows a growing log file: feeds complete new lines to the watcher, keeps the last few.
class LogWatcher {
 public:
  LogWatcher(fs::path path, int keep) : path_(std::move(path)), keep_(keep) {}

  // Reads what was appended since the last call; returns a reason to stop the run, if any.
  std::optional<std::string> poll(ProgramRun& rec, double courant_limit) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) return std::nullopt;
    in.seekg(offset_);
    std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    offset_ += static_cast<std::streamoff>(chunk.size());
    partial_ += chunk;
    std::optional<std::string> stop;
    std::size_t start = 0, nl;
    while ((nl = partial_.find('\n', start)) != std::string::npos) {
      const std::string line = partial_.substr(start, nl - start);
      start = nl + 1;
      if (auto r = inspect(line, rec, courant_limit); r && !stop) stop = r;
    }
    partial_.erase(0, start);
    return stop;
  }

  std::string tail() const {
    std::string out;
    for (const auto& l : lines_) out += "    | " + l + "\n";
    if (!partial_.empty()) out += "    | " + partial_ + "\n";
    return out;
  }
  bool saw_fatal() const { return fatal_; }

 private:
  std::optional<std::string> inspect(const std::string& line, ProgramRun& rec, double courant_limit) {
    if (!line.empty()) {
      lines_.push_back(line);
      if (static_cast<int>(lines_.size()) > keep_) lines_.pop_front();
    }
    if (line.find("FOAM FATAL") != std::string::npos) fatal_ = true;
    if (line.rfind("Time = ", 0) == 0) ++rec.time_steps;
    const auto c = line.find("Courant Number mean:");
    if (c != std::string::npos) {
      const auto m = line.find("max:", c);
      if (m != std::string::npos) {
        const std::string text = line.substr(m + 4);
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || !std::isfinite(v))
          return fmt::format("the Courant number is not a number ({}): the flow has blown up", line);
        rec.max_courant = std::max(rec.max_courant, v);
        if (v > courant_limit)
          return fmt::format("Courant number {} passed the blow-up limit {} (time step {}): the flow has blown up; "
                             "lower time.max_courant or time.fixed_dt, or coarsen nothing near the fastest flow",
                             v, courant_limit, rec.time_steps);
      }
    }
    return std::nullopt;
  }

  fs::path path_;
  int keep_;
  std::streamoff offset_ = 0;
  std::string partial_;
  std::deque<std::string> lines_;
  bool fatal_ = false;
};

void check(int rc, const char* call) {
  if (rc != 0) throw LibraryError(fmt::format("{} failed: {}", call, std::strerror(rc)));
}

}  // namespace

std::optional<fs::path> find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::string p(path);
  std::size_t start = 0;
  while (start <= p.size()) {
    const auto colon = p.find(':', start);
    const std::string dir = p.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
    if (!dir.empty()) {
      const fs::path candidate = fs::path(dir) / program;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  return std::nullopt;
}

FoamRunner::FoamRunner(fs::path case_dir, fs::path log_dir, RunnerOptions options)
    : case_dir_(std::move(case_dir)), log_dir_(std::move(log_dir)), options_(std::move(options)) {
  project_dir_ = options_.project_dir;
  if (project_dir_.empty()) {
    const char* env = std::getenv("WM_PROJECT_DIR");
    project_dir_ = env && *env ? fs::path(env) : fs::path("/usr/share/openfoam");
  }
  if (!fs::is_regular_file(project_dir_ / "etc" / "controlDict"))
    throw InputError(fmt::format("OpenFOAM not found: {} has no etc/controlDict. Install Debian's OpenFOAM "
                                 "(apt-get install openfoam, or ./suite setup) or set WM_PROJECT_DIR to the folder "
                                 "that holds etc/controlDict",
                                 project_dir_.string()));
  for (const char* program : {"blockMesh", "interFoam"})
    if (!find_on_path(program))
      throw InputError(fmt::format("OpenFOAM not found: '{}' is not on PATH. Install Debian's OpenFOAM "
                                   "(apt-get install openfoam, or ./suite setup) or put its programs on PATH",
                                   program));
  fs::create_directories(log_dir_);
}

fs::path FoamRunner::fresh_log_path(const std::string& name) const {
  fs::path p = log_dir_ / ("log." + name);
  for (int i = 1; fs::exists(p); ++i) p = log_dir_ / fmt::format("log.{}.{}", name, i);
  return p;
}

ProgramRun FoamRunner::run(const std::string& program, const std::vector<std::string>& args, int ranks,
                          const std::string& log_name, bool stoppable) {
  const auto stopping = [this] { return options_.stop_requested && options_.stop_requested(); };
  if (stoppable && stopping()) throw FoamRunStopped(fmt::format("{} not started: the run was asked to stop", program));
  ProgramRun rec;
  rec.program = program;
  rec.log = fresh_log_path(log_name.empty() ? program : log_name);

  std::vector<std::string> argv;
  if (ranks > 1) {
    argv = {"mpirun", "-np", std::to_string(ranks), "--oversubscribe", "--mca", "mpi_yield_when_idle", "1"};
    if (::geteuid() == 0) argv.push_back("--allow-run-as-root");
  }
  argv.push_back(program);
  argv.insert(argv.end(), args.begin(), args.end());
  argv.push_back("-case");
  argv.push_back(fs::absolute(case_dir_).string());
  if (ranks > 1) argv.push_back("-parallel");
  auto env = child_environment(project_dir_);
  auto c_argv = c_strings(argv);
  auto c_env = c_strings(env);

  posix_spawn_file_actions_t actions;
  check(posix_spawn_file_actions_init(&actions), "posix_spawn_file_actions_init");
  check(posix_spawn_file_actions_addopen(&actions, 1, rec.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644),
        "posix_spawn_file_actions_addopen");
  check(posix_spawn_file_actions_adddup2(&actions, 1, 2), "posix_spawn_file_actions_adddup2");
  check(posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0), "posix_spawn_file_actions_addopen");
  pid_t pid = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = posix_spawnp(&pid, argv[0].c_str(), &actions, nullptr, c_argv.data(), c_env.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0)
    throw FoamRunError(fmt::format("could not start {} ({}) for case {}", argv[0], std::strerror(rc),
                                   case_dir_.string()));

  LogWatcher watcher(rec.log, options_.log_tail_lines);
  std::optional<std::string> stop_reason;
  bool asked_to_stop = false;
  int status = 0;
  auto pause = std::chrono::milliseconds(5);
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) throw LibraryError(fmt::format("waitpid for {} failed: {}", program, std::strerror(errno)));
    if (!stop_reason && !asked_to_stop) {
      stop_reason = watcher.poll(rec, options_.courant_blow_up);
      asked_to_stop = !stop_reason && stoppable && stopping();
      if (stop_reason || asked_to_stop) ::kill(pid, SIGTERM);  // mpirun passes it on to its ranks
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(200));
  }
  if (auto r = watcher.poll(rec, options_.courant_blow_up); r && !stop_reason) stop_reason = r;
  rec.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  // A signal that reached the whole job (Slurm's time limit) may have ended the child before the
  // poll above saw the request: ask again after it ended.
  if (asked_to_stop || (!stop_reason && status != 0 && stopping()))
    throw FoamRunStopped(fmt::format("{} stopped after {:.1f} s: the run was asked to stop (log: {})", program,
                                     rec.wall_seconds, rec.log.string()));

  std::string reason;
  if (stop_reason)
    reason = *stop_reason;
  else if (WIFSIGNALED(status))
    reason = fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  else if (WEXITSTATUS(status) != 0)
    reason = fmt::format("exit status {}", WEXITSTATUS(status));
  else if (watcher.saw_fatal())
    reason = "FOAM FATAL ERROR in its log";
  if (!reason.empty())
    throw FoamRunError(fmt::format("OpenFOAM program {} failed: {}.\n  case: {}\n  log:  {}\n  last lines of the log:\n{}",
                                   program, reason, fs::absolute(case_dir_).string(), rec.log.string(),
                                   watcher.tail()));
  return rec;
}

}  // namespace suite::foam_erosion
