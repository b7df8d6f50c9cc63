#pragma once
// Rank-aware logger. info/warn/debug print on rank 0 only (or on every rank when asked);
// error prints on whichever rank calls it, tagged with the rank, because an error is often
// seen by one rank alone. Messages use fmt syntax. Not collective: no call communicates.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <ostream>
#include <string>

#include "core/mpi/comm.hpp"

namespace suite {

enum class LogLevel { debug = 0, info = 1, warn = 2, error = 3, off = 4 };

// Parses "debug", "info", "warn", "error", "off"; throws InputError naming the valid values.
LogLevel parse_log_level(const std::string& text);

struct LoggerOptions {
  LogLevel level = LogLevel::info;
  bool all_ranks = false;          // info/warn/debug from every rank, not only rank 0
  std::ostream* stream = nullptr;  // nullptr: standard error
};

class Logger {
 public:
  Logger(const mpi::Comm& comm, std::string name, LoggerOptions options = {});
  ~Logger();
  Logger(Logger&&) noexcept;
  Logger& operator=(Logger&&) noexcept;

  // Also write this rank's printed lines to `path` (created or appended).
  void add_file(const std::filesystem::path& path);
  void set_level(LogLevel level);

  template <class... A>
  void debug(fmt::format_string<A...> f, A&&... a) {
    emit(LogLevel::debug, f, std::forward<A>(a)...);
  }
  template <class... A>
  void info(fmt::format_string<A...> f, A&&... a) {
    emit(LogLevel::info, f, std::forward<A>(a)...);
  }
  template <class... A>
  void warn(fmt::format_string<A...> f, A&&... a) {
    emit(LogLevel::warn, f, std::forward<A>(a)...);
  }
  template <class... A>
  void error(fmt::format_string<A...> f, A&&... a) {
    emit(LogLevel::error, f, std::forward<A>(a)...);
  }

  // Whether a message at `level` would be printed by this rank.
  bool prints(LogLevel level) const;
  int rank() const { return rank_; }
  void flush();

 private:
  template <class... A>
  void emit(LogLevel level, fmt::format_string<A...> f, A&&... a) {
    if (prints(level)) write(level, fmt::format(f, std::forward<A>(a)...));
  }
  void write(LogLevel level, const std::string& message);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  int rank_ = 0;
  int size_ = 1;
  LogLevel level_ = LogLevel::info;
  bool all_ranks_ = false;
};

}  // namespace suite
