#pragma once
// A fresh scratch folder per test, under the build tree, the same on every rank.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "core/mpi/comm.hpp"

namespace suite::testing {

// <SUITE_TEST_TMP or the system temp/suite-tests>/<test suite>.<test name><suffix>.
inline std::filesystem::path scratch_name(const std::string& suffix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const char* base = std::getenv("SUITE_TEST_TMP");
  const std::filesystem::path root =
      base ? std::filesystem::path(base) : std::filesystem::temp_directory_path() / "suite-tests";
  return root / (std::string(info->test_suite_name()) + "." + info->name() + suffix);
}

// scratch_name(".np<ranks>"), emptied by rank 0 first.
// COLLECTIVE over `comm`.
inline std::filesystem::path scratch_dir(const mpi::Comm& comm) {
  const auto dir = scratch_name(".np" + std::to_string(comm.size()));
  if (comm.is_root()) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  comm.barrier();
  return dir;
}

// scratch_name(""), emptied first; for tests that run in one process.
inline std::filesystem::path scratch_dir() {
  const auto dir = scratch_name("");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The whole text of a file ("" if it cannot be read).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The InputError message of `f`, or "" if it did not throw one.
template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace suite::testing
