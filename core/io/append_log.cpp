#include "core/io/append_log.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "core/errors.hpp"

namespace suite::io {

AppendLog::AppendLog(std::filesystem::path path, std::string what,
                     const std::function<bool(const std::string&)>& complete)
    : path_(std::move(path)), what_(std::move(what)) {
  std::error_code ec;
  bool end_line = false;  // a whole record whose newline was lost is kept, and ended
  if (std::filesystem::exists(path_, ec)) {
    std::ifstream in(path_, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto end = text.rfind('\n');
    const std::size_t keep = end == std::string::npos ? 0 : end + 1;
    if (keep != text.size()) {
      end_line = complete && complete(text.substr(keep));
      if (!end_line) std::filesystem::resize_file(path_, keep);
    }
  }
  file_ = std::fopen(path_.c_str(), "ae");
  if (!file_)
    throw InputError(
        fmt::format("cannot open the {} '{}' for appending: {}", what_, path_.string(), std::strerror(errno)));
  if (end_line) std::fputc('\n', file_);
}

AppendLog::~AppendLog() {
  if (file_) ::fsync(fileno(file_)), std::fclose(file_);
}

void AppendLog::append(const std::string& line) {
  const std::string text = line + "\n";
  const auto now = std::chrono::steady_clock::now();
  const bool sync = now - last_sync_ > std::chrono::seconds(1);
  if (sync) last_sync_ = now;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0 ||
      (sync && ::fsync(fileno(file_)) != 0))
    throw std::runtime_error(fmt::format("cannot write the {} '{}': {}", what_, path_.string(), std::strerror(errno)));
}

}  // namespace suite::io
