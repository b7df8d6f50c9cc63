#include "core/checkpoint/checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <map>

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/h5_file.hpp"
#include "core/log/logger.hpp"
#include "core/run/build_info.hpp"

namespace suite::checkpoint {

namespace {
constexpr const char* kRoot = "/";
const std::string kBlocks = "/blocks/";

std::string count_name(const std::string& name) {
  return kBlocks + name + ".count";
}
}  // namespace

// ----------------------------------------------------------------------------------- Writer

Writer::Writer(const mpi::Comm& comm, std::filesystem::path path, Header header)
    : comm_(comm), path_(std::move(path)), tmp_(path_.string() + ".tmp") {
  file_ = std::make_unique<io::H5File>(comm_, tmp_, io::H5File::Mode::create);
  file_->set_attribute(kRoot, "solver", header.solver);
  file_->set_attribute(kRoot, "format", header.format);
  file_->set_attribute(kRoot, "step", header.step);
  file_->set_attribute(kRoot, "time", header.time);
  file_->set_attribute(kRoot, "suite_version", build_info().version);
  file_->set_attribute(kRoot, "ranks", static_cast<long long>(comm_.size()));
}

Writer::~Writer() {
  if (committed_) return;
  try {
    file_.reset();
    if (comm_.is_root()) std::filesystem::remove(tmp_);
  } catch (...) {  // a destructor must not throw; the temporary is harmless
  }
}

template <class T>
void Writer::write(const std::string& name, std::span<const T> local) {
  const long long n = static_cast<long long>(local.size());
  file_->write_rows<long long>(count_name(name), std::span<const long long>(&n, 1));
  file_->write_rows<T>(kBlocks + name, local);
}

void Writer::write_bytes(const std::string& name, std::span<const std::byte> local) {
  write<unsigned char>(
      name, std::span<const unsigned char>(reinterpret_cast<const unsigned char*>(local.data()), local.size()));
}

void Writer::commit() {
  // Closing flushes the last data and metadata; only a file every rank closed cleanly may
  // replace the previous checkpoints.
  std::string problem;
  try {
    file_->close();
  } catch (const std::exception& e) {
    problem = e.what();
  }
  file_.reset();
  if (!comm_.all(problem.empty()))
    throw LibraryError(fmt::format("checkpoint '{}' was not written completely ({}); the previous checkpoints are kept",
                                   path_.string(), problem.empty() ? "closing failed on another rank" : problem));
  if (comm_.is_root()) {
    try {
      io::fsync_path(tmp_);
      std::filesystem::rename(tmp_, path_);
      io::fsync_path(path_.has_parent_path() ? path_.parent_path() : std::filesystem::path("."));
    } catch (const std::exception& e) {
      problem = e.what();
    }
  }
  comm_.broadcast(problem, 0);
  if (!problem.empty())
    throw LibraryError(fmt::format("checkpoint '{}' could not be committed: {}", path_.string(), problem));
  committed_ = true;
}

#define SUITE_CKPT_INSTANTIATE(T)                                         \
  template void Writer::write<T>(const std::string&, std::span<const T>); \
  template std::vector<T> Reader::read<T>(const std::string&);

// ----------------------------------------------------------------------------------- Reader

Reader::Reader(const mpi::Comm& comm, const std::filesystem::path& path, const std::string& solver, long long format)
    : comm_(comm), path_(path) {
  if (!std::filesystem::exists(path))
    throw InputError(fmt::format("checkpoint '{}' does not exist; list the checkpoint folder and pass an existing file",
                                 path.string()));
  file_ = std::make_unique<io::H5File>(comm_, path_, io::H5File::Mode::read);
  try {
    header_.solver = file_->get_attribute_string(kRoot, "solver");
    header_.format = file_->get_attribute_int(kRoot, "format");
    header_.step = file_->get_attribute_int(kRoot, "step");
    header_.time = file_->get_attribute_double(kRoot, "time");
    header_.suite_version = file_->get_attribute_string(kRoot, "suite_version");
    header_.ranks = file_->get_attribute_int(kRoot, "ranks");
  } catch (const InputError&) {
    throw InputError(fmt::format("'{}' is not a checkpoint of this suite (its header is missing)", path.string()));
  }
  const std::string here = build_info().version;
  if (header_.solver != solver)
    throw InputError(fmt::format("checkpoint '{}' was written by '{}', not '{}'; pass a checkpoint of {}",
                                 path.string(), header_.solver, solver, solver));
  if (header_.format != format || header_.suite_version != here)
    throw InputError(
        fmt::format("checkpoint '{}' has format {} from suite {}; this build reads format {} of suite {}; "
                    "finish the run with the build that wrote it, or start from scratch",
                    path.string(), header_.format, header_.suite_version, format, here));
  if (header_.ranks != comm_.size())
    throw InputError(
        fmt::format("checkpoint '{}' was written by {} ranks but this run has {}; a bit-for-bit "
                    "restart needs the same count: run with {} ranks (e.g. srun -n {})",
                    path.string(), header_.ranks, comm_.size(), header_.ranks, header_.ranks));
}

Reader::~Reader() = default;

template <class T>
std::vector<T> Reader::read(const std::string& name) {
  if (!file_->exists(kBlocks + name))
    throw InputError(fmt::format("checkpoint '{}' has no array '{}'", path_.string(), name));
  const auto counts = file_->read_all<long long>(count_name(name));
  long long offset = 0;
  for (int r = 0; r < comm_.rank(); ++r) offset += counts[static_cast<std::size_t>(r)];
  return file_->read_rows<T>(kBlocks + name, offset, counts[static_cast<std::size_t>(comm_.rank())]);
}

std::vector<std::byte> Reader::read_bytes(const std::string& name) {
  const auto v = read<unsigned char>(name);
  std::vector<std::byte> out(v.size());
  std::transform(v.begin(), v.end(), out.begin(), [](unsigned char c) { return std::byte{c}; });
  return out;
}

SUITE_CKPT_INSTANTIATE(double)
SUITE_CKPT_INSTANTIATE(float)
SUITE_CKPT_INSTANTIATE(int)
SUITE_CKPT_INSTANTIATE(long long)
SUITE_CKPT_INSTANTIATE(unsigned char)
#undef SUITE_CKPT_INSTANTIATE

// ---------------------------------------------------------------------------------- finding

std::filesystem::path file_name(const std::filesystem::path& dir, const std::string& prefix, long long step) {
  return dir / fmt::format("{}_{:09d}.h5", prefix, step);
}

namespace {
std::map<long long, std::filesystem::path> list(const std::filesystem::path& dir, const std::string& prefix) {
  std::map<long long, std::filesystem::path> found;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.size() <= prefix.size() + 4 || n.rfind(prefix + "_", 0) != 0 || !n.ends_with(".h5")) continue;
    const char* first = n.data() + prefix.size() + 1;
    const char* last = n.data() + n.size() - 3;
    long long step = 0;
    if (std::from_chars(first, last, step).ptr == last) found[step] = e.path();
  }
  return found;
}
}  // namespace

std::optional<std::filesystem::path> latest(const std::filesystem::path& dir, const std::string& prefix) {
  auto found = list(dir, prefix);
  if (found.empty()) return std::nullopt;
  return found.rbegin()->second;
}

std::optional<std::filesystem::path> latest(const mpi::Comm& comm, const std::filesystem::path& dir,
                                            const std::string& prefix) {
  std::string found;
  if (comm.is_root()) found = latest(dir, prefix).value_or(std::filesystem::path()).string();
  comm.broadcast(found, 0);
  if (found.empty()) return std::nullopt;
  return std::filesystem::path(found);
}

std::filesystem::path restart_path(const mpi::Comm& comm, const std::filesystem::path& dir, const std::string& prefix,
                                   const std::string& which) {
  if (which != "latest") return which;
  const auto found = latest(comm, dir, prefix);
  if (!found)
    throw InputError(fmt::format("--restart latest: no checkpoint in '{}'; run without --restart to start from t = 0",
                                 dir.string()));
  return *found;
}

int discard_after(const std::filesystem::path& dir, const std::string& prefix, long long step) {
  int removed = 0;
  for (const auto& [s, path] : list(dir, prefix)) {
    if (s > step) removed += std::filesystem::remove(path) ? 1 : 0;
  }
  return removed;
}

void discard_after(const mpi::Comm& comm, const std::filesystem::path& dir, const std::string& prefix, long long step,
                   Logger& log) {
  if (!comm.is_root()) return;
  const int removed = discard_after(dir, prefix, step);
  if (removed > 0)
    log.warn("removed {} checkpoint(s) after step {} left by an earlier run", removed, std::max(step, 0LL));
}

void prune(const std::filesystem::path& dir, const std::string& prefix, int keep) {
  auto found = list(dir, prefix);
  int excess = static_cast<int>(found.size()) - keep;
  for (auto it = found.begin(); excess > 0 && it != found.end(); ++it, --excess) std::filesystem::remove(it->second);
}

}  // namespace suite::checkpoint
