#pragma once
// An append-only text file of one record per line that survives kills and node failures: each
// line is flushed as it is written (a killed process loses nothing written) and fsynced at most
// once a second and on close (a node failure loses at most the last second), so fast producers
// are not disk-bound. Reopening cuts off a line torn by a kill mid-write, so new lines start on a
// line of their own. Used by the study ledger and the seed batch's results table. Not collective.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

namespace suite::io {

class AppendLog {
 public:
  // `complete`: is a last line without its newline a whole record (then it is kept and ended)?
  // By default such a line is torn and cut off. `what` names the file in messages ("study ledger").
  AppendLog(std::filesystem::path path, std::string what,
            const std::function<bool(const std::string&)>& complete = nullptr);
  ~AppendLog();
  AppendLog(const AppendLog&) = delete;
  AppendLog& operator=(const AppendLog&) = delete;

  void append(const std::string& line);  // `line` without its newline; throws on a write error
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::string what_;
  std::FILE* file_ = nullptr;
  std::chrono::steady_clock::time_point last_sync_{};
};

}  // namespace suite::io
