#include "core/io/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/errors.hpp"

namespace suite::io {

namespace {
[[noreturn]] void fail(const char* what, const std::filesystem::path& p, int error) {
  throw LibraryError(fmt::format("{} '{}' failed: {}", what, p.string(), std::strerror(error)));
}
}  // namespace

void fsync_path(const std::filesystem::path& path) {
  const bool is_dir = std::filesystem::is_directory(path);
  const int fd = ::open(path.c_str(), is_dir ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) fail("open for fsync of", path, errno);
  const int rc = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  // Some file systems cannot fsync a folder (EINVAL); the rename is then as durable as they allow.
  if (rc != 0 && !(is_dir && error == EINVAL)) fail("fsync of", path, error);
}

void write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  // A temporary name of its own (mkstemp), so that processes writing the same file at once (a
  // Slurm array's tasks adding the same seeds to a register) each rename a whole file; the last
  // rename wins.
  std::string name = path.string() + ".tmp.XXXXXX";
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    throw InputError(fmt::format("cannot write '{}': {}; check that the folder exists and is writable", path.string(),
                                 std::strerror(errno)));
  }
  const std::filesystem::path tmp = name;
  ::fchmod(fd, 0644);  // mkstemp's 0600, as a plain open would have made it
  auto give_up = [&](const char* what) {
    const int error = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    fail(what, tmp, error);
  };
  std::size_t done = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      give_up("write of");
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) give_up("fsync of");
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(tmp.c_str());
    fail("close of", tmp, error);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(tmp.c_str());
    fail("rename to", path, error);
  }
  fsync_path(path.has_parent_path() ? path.parent_path() : std::filesystem::path("."));
}

}  // namespace suite::io
