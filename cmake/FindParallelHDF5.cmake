# Parallel HDF5 (Debian: libhdf5-openmpi-dev) as the imported target Suite::HDF5.
# HDF5_PREFER_PARALLEL matters: if serial libhdf5-dev is ever installed, FindHDF5 would take h5cc.
set(HDF5_PREFER_PARALLEL TRUE)
find_package(HDF5 REQUIRED COMPONENTS C)
if(NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR "HDF5 ${HDF5_VERSION} was found but it is serial; the suite writes one "
                      "collective file per output step. Install libhdf5-openmpi-dev.")
endif()
if(NOT TARGET Suite::HDF5)
  add_library(Suite::HDF5 INTERFACE IMPORTED)
  target_include_directories(Suite::HDF5 INTERFACE ${HDF5_INCLUDE_DIRS})
  target_link_libraries(Suite::HDF5 INTERFACE ${HDF5_LIBRARIES} MPI::MPI_C)
  target_compile_definitions(Suite::HDF5 INTERFACE ${HDF5_DEFINITIONS})
endif()
message(STATUS "parallel HDF5 ${HDF5_VERSION}: ${HDF5_INCLUDE_DIRS}")
