#include "core/run/signals.hpp"

#include <algorithm>
#include <atomic>
#include <csignal>

#include "core/errors.hpp"

namespace suite {

namespace {
// Written only by the handler and the poll; lock-free atomics are async-signal-safe.
std::atomic<int> g_request{0};
std::atomic<int> g_signal{0};
std::atomic<bool> g_installed{false};
struct sigaction g_old_usr1, g_old_term, g_old_int;
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_signal(int sig) {
  const int req = sig == SIGUSR1 ? static_cast<int>(SignalRequest::checkpoint)
                                 : static_cast<int>(SignalRequest::checkpoint_and_stop);
  int cur = g_request.load();
  while (cur < req && !g_request.compare_exchange_weak(cur, req)) {
  }
  g_signal.store(sig);
}
}  // namespace

SignalWatcher::SignalWatcher(std::filesystem::path request_dir) : request_dir_(std::move(request_dir)) {
  if (g_installed.exchange(true)) throw LibraryError("only one SignalWatcher may exist at a time");
  g_request = 0;
  g_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGUSR1, &sa, &g_old_usr1);
  sigaction(SIGTERM, &sa, &g_old_term);
  sigaction(SIGINT, &sa, &g_old_int);
}

SignalWatcher::~SignalWatcher() {
  sigaction(SIGUSR1, &g_old_usr1, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
  sigaction(SIGINT, &g_old_int, nullptr);
  g_installed = false;
}

int SignalWatcher::last_signal() const {
  return g_signal.load();
}

SignalRequest SignalWatcher::poll(const mpi::Comm& comm) {
  int mine = g_request.exchange(0);
  if (!request_dir_.empty() && comm.is_root()) {
    // A request file counts once: it is removed when seen.
    const auto take = [&](const char* name, SignalRequest r) {
      std::error_code ec;
      if (std::filesystem::remove(request_dir_ / name, ec)) mine = std::max(mine, static_cast<int>(r));
    };
    take("checkpoint_now", SignalRequest::checkpoint);
    take("stop", SignalRequest::checkpoint_and_stop);
  }
  return static_cast<SignalRequest>(comm.max(static_cast<long long>(mine)));
}

const char* describe(SignalRequest r) {
  switch (r) {
    case SignalRequest::none:
      return "none";
    case SignalRequest::checkpoint:
      return "checkpoint (SIGUSR1 or a checkpoint_now file)";
    case SignalRequest::checkpoint_and_stop:
      return "checkpoint and stop (SIGTERM, SIGINT or a stop file)";
  }
  return "?";
}

}  // namespace suite
