#include "core/io/h5_file.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace suite::io {

template <>
hid_t h5_type<double>() {
  return H5T_NATIVE_DOUBLE;
}
template <>
hid_t h5_type<float>() {
  return H5T_NATIVE_FLOAT;
}
template <>
hid_t h5_type<int>() {
  return H5T_NATIVE_INT;
}
template <>
hid_t h5_type<long long>() {
  return H5T_NATIVE_LLONG;
}
template <>
hid_t h5_type<unsigned char>() {
  return H5T_NATIVE_UCHAR;
}

namespace {

// Closes an HDF5 handle at scope exit.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

hid_t collective_transfer() {
  hid_t dxpl = static_cast<hid_t>(SUITE_H5_CHECK(H5Pcreate(H5P_DATASET_XFER)));
  SUITE_H5_CHECK(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE));
  return dxpl;
}

}  // namespace

H5File::H5File(const mpi::Comm& comm, const std::filesystem::path& path, Mode mode) : comm_(comm), path_(path) {
  // Errors are reported through check_h5 with HDF5's own description; no automatic printing.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Handle fapl{static_cast<hid_t>(SUITE_H5_CHECK(H5Pcreate(H5P_FILE_ACCESS))), H5Pclose};
  SUITE_H5_CHECK(H5Pset_fapl_mpio(fapl.id, comm.raw(), MPI_INFO_NULL));
  SUITE_H5_CHECK(H5Pset_all_coll_metadata_ops(fapl.id, true));
  SUITE_H5_CHECK(H5Pset_coll_metadata_write(fapl.id, true));
  if (mode == Mode::create) {
    file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id);
  } else {
    file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.id);
  }
  if (file_ < 0) {
    H5Eclear2(H5E_DEFAULT);
    throw InputError(fmt::format(
        "cannot {} HDF5 file '{}': {}", mode == Mode::create ? "create" : "open", path.string(),
        mode == Mode::create ? "check that its folder exists and is writable" : "it is missing or not an HDF5 file"));
  }
}

H5File::~H5File() {
  if (file_ >= 0) H5Fclose(file_);
}

void H5File::close() {
  if (file_ < 0) return;
  const hid_t f = file_;
  file_ = -1;
  const herr_t flushed = H5Fflush(f, H5F_SCOPE_GLOBAL);
  const herr_t closed = H5Fclose(f);
  SUITE_H5_CHECK(flushed);
  SUITE_H5_CHECK(closed);
}

hid_t H5File::dataset_for_write(const std::string& name, hid_t type, const std::vector<hsize_t>& dims) {
  Handle space{
      static_cast<hid_t>(SUITE_H5_CHECK(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr))),
      H5Sclose};
  Handle lcpl{static_cast<hid_t>(SUITE_H5_CHECK(H5Pcreate(H5P_LINK_CREATE))), H5Pclose};
  SUITE_H5_CHECK(H5Pset_create_intermediate_group(lcpl.id, 1));
  return static_cast<hid_t>(
      SUITE_H5_CHECK(H5Dcreate2(file_, name.c_str(), type, space.id, lcpl.id, H5P_DEFAULT, H5P_DEFAULT)));
}

template <class T>
RowRange H5File::write_rows(const std::string& name, std::span<const T> local, std::size_t cols) {
  if (cols == 0 || local.size() % cols != 0)
    throw LibraryError(
        fmt::format("write_rows('{}'): {} values is not a whole number of rows of {}", name, local.size(), cols));
  RowRange r;
  r.count = static_cast<long long>(local.size() / cols);
  r.offset = comm_.exclusive_prefix_sum(r.count);
  r.total = comm_.sum(r.count);
  std::vector<hsize_t> dims{static_cast<hsize_t>(r.total)};
  if (cols > 1) dims.push_back(cols);
  Handle dset{dataset_for_write(name, h5_type<T>(), dims), H5Dclose};
  Handle fspace{static_cast<hid_t>(SUITE_H5_CHECK(H5Dget_space(dset.id))), H5Sclose};
  std::vector<hsize_t> start{static_cast<hsize_t>(r.offset)}, count{static_cast<hsize_t>(r.count)};
  if (cols > 1) {
    start.push_back(0);
    count.push_back(cols);
  }
  Handle mspace{
      static_cast<hid_t>(SUITE_H5_CHECK(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr))),
      H5Sclose};
  if (r.count > 0) {
    SUITE_H5_CHECK(H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr));
  } else {
    SUITE_H5_CHECK(H5Sselect_none(fspace.id));
    SUITE_H5_CHECK(H5Sselect_none(mspace.id));
  }
  if (r.total == 0) return r;  // an empty dataset: nothing to transfer (HDF5 rejects it)
  Handle dxpl{collective_transfer(), H5Pclose};
  const T dummy{};
  SUITE_H5_CHECK(H5Dwrite(dset.id, h5_type<T>(), mspace.id, fspace.id, dxpl.id, local.empty() ? &dummy : local.data()));
  return r;
}

template <class T>
void H5File::write_replicated(const std::string& name, std::span<const T> values) {
  std::vector<hsize_t> dims{values.size()};
  Handle dset{dataset_for_write(name, h5_type<T>(), dims), H5Dclose};
  Handle fspace{static_cast<hid_t>(SUITE_H5_CHECK(H5Dget_space(dset.id))), H5Sclose};
  Handle mspace{static_cast<hid_t>(SUITE_H5_CHECK(H5Screate_simple(1, dims.data(), nullptr))), H5Sclose};
  if (!comm_.is_root() || values.empty()) {
    SUITE_H5_CHECK(H5Sselect_none(fspace.id));
    SUITE_H5_CHECK(H5Sselect_none(mspace.id));
  }
  Handle dxpl{collective_transfer(), H5Pclose};
  const T dummy{};
  SUITE_H5_CHECK(
      H5Dwrite(dset.id, h5_type<T>(), mspace.id, fspace.id, dxpl.id, values.empty() ? &dummy : values.data()));
}

std::vector<long long> H5File::shape(const std::string& name) {
  if (!exists(name)) throw InputError(fmt::format("HDF5 file '{}' has no dataset '{}'", path_.string(), name));
  Handle dset{static_cast<hid_t>(SUITE_H5_CHECK(H5Dopen2(file_, name.c_str(), H5P_DEFAULT))), H5Dclose};
  Handle space{static_cast<hid_t>(SUITE_H5_CHECK(H5Dget_space(dset.id))), H5Sclose};
  const int rank = static_cast<int>(SUITE_H5_CHECK(H5Sget_simple_extent_ndims(space.id)));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  SUITE_H5_CHECK(H5Sget_simple_extent_dims(space.id, dims.data(), nullptr));
  return {dims.begin(), dims.end()};
}

bool H5File::exists(const std::string& name) {
  // Walk the path so a missing intermediate group is "no" rather than an error.
  std::size_t pos = 0;
  while ((pos = name.find('/', pos + 1)) != std::string::npos) {
    if (H5Lexists(file_, name.substr(0, pos).c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return H5Lexists(file_, name.c_str(), H5P_DEFAULT) > 0;
}

template <class T>
std::vector<T> H5File::read_rows(const std::string& name, long long offset, long long count) {
  const auto dims = shape(name);
  const hsize_t cols = dims.size() > 1 ? static_cast<hsize_t>(dims[1]) : 1;
  if (offset < 0 || count < 0 || offset + count > dims[0])
    throw InputError(fmt::format("HDF5 file '{}': rows [{}, {}) of '{}' are outside its {} rows", path_.string(),
                                 offset, offset + count, name, dims[0]));
  Handle dset{static_cast<hid_t>(SUITE_H5_CHECK(H5Dopen2(file_, name.c_str(), H5P_DEFAULT))), H5Dclose};
  Handle fspace{static_cast<hid_t>(SUITE_H5_CHECK(H5Dget_space(dset.id))), H5Sclose};
  std::vector<hsize_t> start{static_cast<hsize_t>(offset)}, cnt{static_cast<hsize_t>(count)};
  if (dims.size() > 1) {
    start.push_back(0);
    cnt.push_back(cols);
  }
  Handle mspace{static_cast<hid_t>(SUITE_H5_CHECK(H5Screate_simple(static_cast<int>(cnt.size()), cnt.data(), nullptr))),
                H5Sclose};
  std::vector<T> out(static_cast<std::size_t>(count) * cols);
  if (dims[0] == 0) return out;  // an empty dataset: nothing to transfer
  if (count > 0) {
    SUITE_H5_CHECK(H5Sselect_hyperslab(fspace.id, H5S_SELECT_SET, start.data(), nullptr, cnt.data(), nullptr));
  } else {
    SUITE_H5_CHECK(H5Sselect_none(fspace.id));
    SUITE_H5_CHECK(H5Sselect_none(mspace.id));
  }
  Handle dxpl{collective_transfer(), H5Pclose};
  T dummy{};
  SUITE_H5_CHECK(H5Dread(dset.id, h5_type<T>(), mspace.id, fspace.id, dxpl.id, out.empty() ? &dummy : out.data()));
  return out;
}

template <class T>
std::vector<T> H5File::read_all(const std::string& name) {
  return read_rows<T>(name, 0, shape(name)[0]);
}

#define SUITE_H5_INSTANTIATE(T)                                                                 \
  template RowRange H5File::write_rows<T>(const std::string&, std::span<const T>, std::size_t); \
  template void H5File::write_replicated<T>(const std::string&, std::span<const T>);            \
  template std::vector<T> H5File::read_rows<T>(const std::string&, long long, long long);       \
  template std::vector<T> H5File::read_all<T>(const std::string&);
SUITE_H5_INSTANTIATE(double)
SUITE_H5_INSTANTIATE(float)
SUITE_H5_INSTANTIATE(int)
SUITE_H5_INSTANTIATE(long long)
SUITE_H5_INSTANTIATE(unsigned char)
#undef SUITE_H5_INSTANTIATE

// ----------------------------------------------------------------------------------- attributes

namespace {
void write_attr(hid_t file, const std::string& object, const std::string& attr, hid_t type, const void* data) {
  Handle obj{static_cast<hid_t>(SUITE_H5_CHECK(H5Oopen(file, object.c_str(), H5P_DEFAULT))), H5Oclose};
  if (H5Aexists(obj.id, attr.c_str()) > 0) SUITE_H5_CHECK(H5Adelete(obj.id, attr.c_str()));
  Handle space{static_cast<hid_t>(SUITE_H5_CHECK(H5Screate(H5S_SCALAR))), H5Sclose};
  Handle a{
      static_cast<hid_t>(SUITE_H5_CHECK(H5Acreate2(obj.id, attr.c_str(), type, space.id, H5P_DEFAULT, H5P_DEFAULT))),
      H5Aclose};
  SUITE_H5_CHECK(H5Awrite(a.id, type, data));
}
Handle open_attr(hid_t file, const std::filesystem::path& path, const std::string& object, const std::string& attr) {
  Handle obj{static_cast<hid_t>(SUITE_H5_CHECK(H5Oopen(file, object.c_str(), H5P_DEFAULT))), H5Oclose};
  if (H5Aexists(obj.id, attr.c_str()) <= 0)
    throw InputError(fmt::format("HDF5 file '{}': '{}' has no attribute '{}'", path.string(), object, attr));
  return Handle{static_cast<hid_t>(SUITE_H5_CHECK(H5Aopen(obj.id, attr.c_str(), H5P_DEFAULT))), H5Aclose};
}
}  // namespace

void H5File::set_attribute(const std::string& object, const std::string& attr, double value) {
  write_attr(file_, object, attr, H5T_NATIVE_DOUBLE, &value);
}
void H5File::set_attribute(const std::string& object, const std::string& attr, long long value) {
  write_attr(file_, object, attr, H5T_NATIVE_LLONG, &value);
}
void H5File::set_attribute(const std::string& object, const std::string& attr, const std::string& value) {
  Handle type{static_cast<hid_t>(SUITE_H5_CHECK(H5Tcopy(H5T_C_S1))), H5Tclose};
  SUITE_H5_CHECK(H5Tset_size(type.id, value.empty() ? 1 : value.size()));
  SUITE_H5_CHECK(H5Tset_strpad(type.id, H5T_STR_NULLPAD));
  const std::string padded = value.empty() ? std::string(1, '\0') : value;
  write_attr(file_, object, attr, type.id, padded.data());
}

double H5File::get_attribute_double(const std::string& object, const std::string& attr) {
  Handle a = open_attr(file_, path_, object, attr);
  double v = 0;
  SUITE_H5_CHECK(H5Aread(a.id, H5T_NATIVE_DOUBLE, &v));
  return v;
}
long long H5File::get_attribute_int(const std::string& object, const std::string& attr) {
  Handle a = open_attr(file_, path_, object, attr);
  long long v = 0;
  SUITE_H5_CHECK(H5Aread(a.id, H5T_NATIVE_LLONG, &v));
  return v;
}
std::string H5File::get_attribute_string(const std::string& object, const std::string& attr) {
  Handle a = open_attr(file_, path_, object, attr);
  Handle type{static_cast<hid_t>(SUITE_H5_CHECK(H5Aget_type(a.id))), H5Tclose};
  const std::size_t n = H5Tget_size(type.id);
  std::string v(n, '\0');
  SUITE_H5_CHECK(H5Aread(a.id, type.id, v.data()));
  v.erase(v.find_last_not_of('\0') + 1);
  return v;
}

}  // namespace suite::io
