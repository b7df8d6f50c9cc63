#pragma once
// Error types of the suite and the always-on checks of library return codes.
//
// InputError: something the user can fix (a file, a key, a value, a command-line argument).
//   Its message is one line that names the place and says what would be valid. Executables
//   print it and exit with status 2, never with a stack trace.
// LibraryError: a failed MPI/HDF5/PETSc/OpenCV call. Its message names the call, the source
//   location and the library's own description of the code.
#include <source_location>
#include <stdexcept>
#include <string>

namespace suite {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LibraryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "file.cpp:123 (function)" for messages.
std::string where(const std::source_location& loc);

// Throws LibraryError unless rc == MPI_SUCCESS. `call` is the text of the call.
void check_mpi(int rc, const char* call, std::source_location loc = std::source_location::current());

// Throws LibraryError if an HDF5 identifier or status is negative; the message includes the
// innermost entry of HDF5's error stack. Returns `id` so it can wrap H5Fcreate and friends.
long long check_h5(long long id, const char* call, std::source_location loc = std::source_location::current());

}  // namespace suite

// Macros keep the text of the call in the message.
#define SUITE_MPI_CHECK(call) ::suite::check_mpi((call), #call)
#define SUITE_H5_CHECK(call) ::suite::check_h5(static_cast<long long>(call), #call)
