#include "core/petsc/petsc_session.hpp"

#include <cctype>
#include <sstream>

#include "core/petsc/petsc_check.hpp"

namespace suite {

namespace {

// The option names of an options string: the words that start with '-' and a letter (a value
// such as -1e-3 starts with a digit or a dot).
std::vector<std::string> option_names(const std::string& options) {
  std::vector<std::string> names;
  std::istringstream words(options);
  for (std::string w; words >> w;)
    if (w.size() > 1 && w[0] == '-' && std::isalpha(static_cast<unsigned char>(w[1]))) names.push_back(w);
  return names;
}

}  // namespace

PetscSession::PetscSession(const mpi::Comm& comm, const std::string& options) : names_(option_names(options)) {
  PETSC_COMM_WORLD = comm.raw();
  SUITE_PETSC_CHECK(PetscInitializeNoArguments());
  SUITE_PETSC_CHECK(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  if (!options.empty()) SUITE_PETSC_CHECK(PetscOptionsInsertString(nullptr, options.c_str()));
}

std::vector<std::string> PetscSession::unused_options() const {
  std::vector<std::string> unused;
  for (const auto& name : names_) {
    PetscBool used = PETSC_FALSE;
    // The database keeps names without their leading '-'.
    SUITE_PETSC_CHECK(PetscOptionsUsed(nullptr, name.c_str() + 1, &used));
    if (!used) unused.push_back(name);
  }
  return unused;
}

PetscSession::~PetscSession() {
  PetscPopErrorHandler();
  PetscFinalize();
}

}  // namespace suite
