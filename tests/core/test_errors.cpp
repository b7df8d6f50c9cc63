// The error-check wrappers turn library return codes into messages that name the call.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>

#include "core/errors.hpp"

namespace {

std::string library_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const suite::LibraryError& e) {
    return e.what();
  }
  return "";
}

TEST(Errors, MpiFailureNamesTheCallAndMpisText) {
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  const std::string msg = library_error_of([] {
    int x = 0;
    SUITE_MPI_CHECK(MPI_Bcast(&x, -1, MPI_INT, 0, MPI_COMM_WORLD));  // negative count
  });
  EXPECT_NE(msg.find("MPI call MPI_Bcast(&x, -1, MPI_INT, 0, MPI_COMM_WORLD) failed"), std::string::npos) << msg;
  EXPECT_NE(msg.find("test_errors.cpp"), std::string::npos) << msg;
  EXPECT_NO_THROW(SUITE_MPI_CHECK(MPI_SUCCESS));
}

TEST(Errors, Hdf5FailureIncludesTheInnermostStackEntry) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string msg =
      library_error_of([] { SUITE_H5_CHECK(H5Fopen("/nonexistent/x.h5", H5F_ACC_RDONLY, H5P_DEFAULT)); });
  EXPECT_NE(msg.find("HDF5 call H5Fopen(\"/nonexistent/x.h5\", H5F_ACC_RDONLY, H5P_DEFAULT) failed"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("unable to open file"), std::string::npos) << msg;
  EXPECT_EQ(SUITE_H5_CHECK(5), 5);
}

}  // namespace
