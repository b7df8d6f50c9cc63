# METIS 5 (Debian: libmetis-dev) ships neither a CMake config nor a .pc file.
# Gives Suite::METIS.
find_path(METIS_INCLUDE_DIR metis.h REQUIRED)
find_library(METIS_LIBRARY metis REQUIRED)
if(NOT TARGET Suite::METIS)
  add_library(Suite::METIS UNKNOWN IMPORTED)
  set_target_properties(Suite::METIS PROPERTIES IMPORTED_LOCATION ${METIS_LIBRARY}
                        INTERFACE_INCLUDE_DIRECTORIES ${METIS_INCLUDE_DIR})
endif()
message(STATUS "METIS: ${METIS_LIBRARY}")
