#pragma once
// Checkpoint files for bit-for-bit restart on the same rank count.
//
// One HDF5 file per checkpoint, written collectively: every named array is stored as the
// concatenation of the ranks' blocks plus a per-rank count, so each rank reads back exactly
// the bytes it wrote. The file is written under "<name>.tmp", flushed to disk, and renamed by
// rank 0 only when complete: a run killed mid-write leaves the previous checkpoint intact.
//
// The header records the solver, its checkpoint format version, the suite version, the rank
// count, the step and the time. The reader refuses a file whose solver, format, suite version
// or rank count differ, with a message that says what to do.
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"

namespace suite {
class Logger;
}

namespace suite::io {
class H5File;
}

namespace suite::checkpoint {

struct Header {
  std::string solver;    // e.g. "mpm2grid"
  long long format = 1;  // the solver's checkpoint layout version
  long long step = 0;
  double time = 0.0;  // simulated time, s
  // Filled in by the writer / read back by the reader:
  std::string suite_version;
  long long ranks = 0;
};

class Writer {
 public:
  // COLLECTIVE. `path` is the final name, e.g. dir / "checkpoint_000100.h5".
  Writer(const mpi::Comm& comm, std::filesystem::path path, Header header);
  // COLLECTIVE. Without commit(): the temporary file is removed, no checkpoint appears.
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // This rank's block of array `name` (any length, zero included). COLLECTIVE.
  // T: double, float, int, long long, unsigned char.
  template <class T>
  void write(const std::string& name, std::span<const T> local);
  // Raw bytes of trivially copyable state (counters, small structs). COLLECTIVE.
  void write_bytes(const std::string& name, std::span<const std::byte> local);

  // Close, fsync, rename to the final name, fsync the folder. COLLECTIVE.
  void commit();

 private:
  mpi::Comm comm_;
  std::filesystem::path path_, tmp_;
  std::unique_ptr<io::H5File> file_;
  bool committed_ = false;
};

class Reader {
 public:
  // COLLECTIVE. Throws InputError if the file is not a checkpoint of `solver` with `format`,
  // or was written by another suite version or rank count.
  Reader(const mpi::Comm& comm, const std::filesystem::path& path, const std::string& solver, long long format);
  ~Reader();
  const Header& header() const { return header_; }

  template <class T>
  std::vector<T> read(const std::string& name);  // this rank's block. COLLECTIVE.
  std::vector<std::byte> read_bytes(const std::string& name);

 private:
  mpi::Comm comm_;
  std::filesystem::path path_;
  std::unique_ptr<io::H5File> file_;
  Header header_;
};

// File name for a step: "<prefix>_<step, 9 digits>.h5".
std::filesystem::path file_name(const std::filesystem::path& dir, const std::string& prefix, long long step);
// The checkpoint with the highest step in `dir` ("<prefix>_*.h5", temporaries ignored).
std::optional<std::filesystem::path> latest(const std::filesystem::path& dir, const std::string& prefix);
// The same, looked up on rank 0 and broadcast, so every rank opens the same file. COLLECTIVE.
std::optional<std::filesystem::path> latest(const mpi::Comm& comm, const std::filesystem::path& dir,
                                            const std::string& prefix);
// Deletes all but the newest `keep` checkpoints. Not collective: call on rank 0.
// The checkpoint a `--restart WHICH` names: "latest" is the newest in `dir` (COLLECTIVE), anything
// else a path. InputError when `dir` holds none, saying to run without --restart.
std::filesystem::path restart_path(const mpi::Comm& comm, const std::filesystem::path& dir, const std::string& prefix,
                                   const std::string& which);
void prune(const std::filesystem::path& dir, const std::string& prefix, int keep);
// Deletes the checkpoints with a step above `step`: the future of a run that is being started
// again (step = -1 for a fresh start, the restart step otherwise), so that they can neither
// outrank the new run's checkpoints in prune() nor be taken by latest(). Returns how many.
// Not collective: call on rank 0.
int discard_after(const std::filesystem::path& dir, const std::string& prefix, long long step);
// The same done by rank 0 for a run starting at `step`, with a warning in `log` naming how many
// checkpoints of an earlier run were removed. Call on every rank; nothing is communicated.
void discard_after(const mpi::Comm& comm, const std::filesystem::path& dir, const std::string& prefix, long long step,
                   Logger& log);

}  // namespace suite::checkpoint
