#pragma once
// One HDF5 file opened by every rank of a communicator (parallel HDF5, MPI-IO driver).
//
// Distributed arrays are written by rows: each rank passes its local rows (row-major, `cols`
// values per row) and the rows land in rank order, rank 0's first. A dataset is 1D when
// cols == 1 and 2D (rows x cols) otherwise. Writes use collective MPI-IO transfers.
// Every member is COLLECTIVE: all ranks call it in the same order with the same names; the
// destructor too (it closes the file), so an H5File must not outlive a rank-local exception.
#include <hdf5.h>

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/mpi/comm.hpp"

namespace suite::io {

// Where this rank's rows went, and the global row count.
struct RowRange {
  long long offset = 0;
  long long count = 0;
  long long total = 0;
};

// Supported element types: double, float, int, long long, unsigned char.
template <class T>
hid_t h5_type();

class H5File {
 public:
  enum class Mode { create, read };
  H5File(const mpi::Comm& comm, const std::filesystem::path& path, Mode mode);
  ~H5File();
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const mpi::Comm& comm() const { return comm_; }

  // `local.size()` must be a multiple of `cols`. Intermediate groups in `name` are created.
  template <class T>
  RowRange write_rows(const std::string& name, std::span<const T> local, std::size_t cols = 1);

  // The same small array on every rank, written once (e.g. a grid origin).
  template <class T>
  void write_replicated(const std::string& name, std::span<const T> values);

  // Rows [offset, offset + count) of a dataset, `cols` values per row.
  template <class T>
  std::vector<T> read_rows(const std::string& name, long long offset, long long count);
  // The whole dataset on every rank (for small arrays and tests).
  template <class T>
  std::vector<T> read_all(const std::string& name);

  std::vector<long long> shape(const std::string& name);
  bool exists(const std::string& name);

  // Attributes on a dataset or group ("/" for the file). Every rank passes the same value.
  void set_attribute(const std::string& object, const std::string& attr, double value);
  void set_attribute(const std::string& object, const std::string& attr, long long value);
  void set_attribute(const std::string& object, const std::string& attr, const std::string& value);
  double get_attribute_double(const std::string& object, const std::string& attr);
  long long get_attribute_int(const std::string& object, const std::string& attr);
  std::string get_attribute_string(const std::string& object, const std::string& attr);

  // Flushes and closes now; throws LibraryError if HDF5 reports a failure (e.g. a full disk).
  // The destructor closes too, ignoring errors.
  void close();

 private:
  hid_t dataset_for_write(const std::string& name, hid_t type, const std::vector<hsize_t>& dims);
  mpi::Comm comm_;
  std::filesystem::path path_;
  hid_t file_ = -1;
};

}  // namespace suite::io
