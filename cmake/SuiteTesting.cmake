# Test helpers. Labels: unit, mpi, regression, slurm, slow (slow is excluded by the test presets).
#
# suite_add_gtest(NAME n SOURCES ... [LIBS ...] LABELS ... [RANKS 1 2] [TIMEOUT s])
#   Builds one GoogleTest executable with the MPI-aware main (tests/support/mpi_gtest_main.cpp)
#   and registers it once per rank count through CMake's MPIEXEC_* variables. Without RANKS it
#   runs once, without mpiexec (MPI singleton init). With RANKS the test names get a .npN suffix.
#
# suite_mpiexec_command(<out-var> <ranks>) gives the launcher prefix used for MPI tests, so
#   regression tests of executables start them exactly like the MPI unit tests.

# Reference data (published tables, Martin & Moyce, the wheat-grain images) is part of the
# repository: data/, its sources and terms in data/README.md.
set(SUITE_DATA_DIR "${PROJECT_SOURCE_DIR}/data")

set(SUITE_MPIEXEC_FLAGS --oversubscribe)
execute_process(COMMAND id -u OUTPUT_VARIABLE SUITE_UID OUTPUT_STRIP_TRAILING_WHITESPACE)
if(SUITE_UID STREQUAL "0")
  list(APPEND SUITE_MPIEXEC_FLAGS --allow-run-as-root)
endif()
# gtest colours its output under mpiexec (ranks get a pty); plain text reads better in CI logs.
set(SUITE_TEST_ENV "GTEST_COLOR=no;OMPI_MCA_rmaps_base_oversubscribe=1")
if(SUITE_SANITIZE)
  # Open MPI keeps allocations until exit by design; leak reports from it are not ours.
  list(APPEND SUITE_TEST_ENV "ASAN_OPTIONS=detect_leaks=0" "UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1")
endif()

function(suite_mpiexec_command out ranks)
  set(${out} ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks} ${SUITE_MPIEXEC_FLAGS}
             ${MPIEXEC_PREFLAGS} PARENT_SCOPE)
endfunction()

function(suite_add_gtest)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS;RANKS" ${ARGN})
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE suite_gtest_main ${T_LIBS} suite_warnings)
  target_compile_definitions(${T_NAME} PRIVATE
    SUITE_SOURCE_DIR="${PROJECT_SOURCE_DIR}" SUITE_DATA_DIR="${SUITE_DATA_DIR}")
  if(NOT T_RANKS)
    add_test(NAME ${T_NAME} COMMAND ${T_NAME})
    set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT}
                         ENVIRONMENT "${SUITE_TEST_ENV}")
    return()
  endif()
  foreach(n IN LISTS T_RANKS)
    suite_mpiexec_command(launcher ${n})
    add_test(NAME ${T_NAME}.np${n}
             COMMAND ${launcher} $<TARGET_FILE:${T_NAME}> ${MPIEXEC_POSTFLAGS})
    set_tests_properties(${T_NAME}.np${n} PROPERTIES LABELS "${T_LABELS}" PROCESSORS ${n}
                         TIMEOUT ${T_TIMEOUT} ENVIRONMENT "${SUITE_TEST_ENV}")
  endforeach()
endfunction()
