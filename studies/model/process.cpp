#include "studies/model/process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

namespace suite::studies {

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& dir, double time_limit_s) {
  ProcessResult r;
  if (argv.empty()) {
    r.reason = "empty command";
    return r;
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const std::string err = (dir / "stderr.txt").string();
  int report[2];  // the child writes errno here if exec fails; closed on a successful exec
  if (::pipe2(report, O_CLOEXEC) != 0) {
    r.reason = fmt::format("cannot create a pipe: {}", std::strerror(errno));
    return r;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid < 0) {
    r.reason = fmt::format("cannot fork: {}", std::strerror(errno));
    ::close(report[0]), ::close(report[1]);
    return r;
  }
  if (pid == 0) {  // child: only async-signal-safe calls until exec
    ::setpgid(0, 0);
    int fail = 0;
    if (::chdir(dir.c_str()) != 0) fail = errno;
    const int fo = fail ? -1 : ::open("stdout.txt", O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    const int fe = fail ? -1 : ::open("stderr.txt", O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (!fail && (fo < 0 || fe < 0)) fail = errno;
    if (!fail) ::dup2(fo, 1), ::dup2(fe, 2), ::execvp(args[0], args.data()), fail = errno;
    [[maybe_unused]] const auto n = ::write(report[1], &fail, sizeof fail);
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  ::close(report[1]);
  int child_errno = 0;
  const bool exec_failed = ::read(report[0], &child_errno, sizeof child_errno) == sizeof child_errno;
  ::close(report[0]);
  int status = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) {  // not our child any more: nothing to wait for
      r.reason = fmt::format("lost track of '{}': {}", argv[0], std::strerror(errno));
      return r;
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (time_limit_s > 0 && elapsed > time_limit_s && !r.timed_out) {
      r.timed_out = true;
      ::kill(-pid, SIGTERM);
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      ::kill(-pid, SIGKILL);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(elapsed < 1.0 ? 2 : 20));
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (exec_failed) {
    r.reason = fmt::format("cannot run '{}' in {}: {}", argv[0], dir.string(), std::strerror(child_errno));
    return r;
  }
  r.started = true;
  r.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (r.timed_out)
    r.reason = fmt::format("'{}' passed its time limit of {} s and was killed", argv[0], time_limit_s);
  else if (r.exit_status != 0)
    r.reason = fmt::format("'{}' exited with status {} (see {})", argv[0], r.exit_status, err);
  return r;
}

}  // namespace suite::studies
