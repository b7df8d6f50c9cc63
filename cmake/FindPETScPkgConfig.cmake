# PETSc through pkg-config (Debian: petsc-dev, 3.18, real, double, 32-bit indices).
# Gives Suite::PETSc. The .pc file does not carry MPI, so it is added here.
find_package(PkgConfig REQUIRED)
pkg_check_modules(PETSC REQUIRED IMPORTED_TARGET PETSc>=3.18)
if(NOT TARGET Suite::PETSc)
  add_library(Suite::PETSc INTERFACE IMPORTED)
  target_link_libraries(Suite::PETSc INTERFACE PkgConfig::PETSC MPI::MPI_C)
endif()
message(STATUS "PETSc ${PETSC_VERSION}: ${PETSC_INCLUDE_DIRS}")
