# Every find_package of the suite, in one place. Versions are Debian 12's (see README).

# --- core: MPI, parallel HDF5, YAML, JSON, logging -------------------------------------
find_package(MPI REQUIRED COMPONENTS C CXX)
include(FindParallelHDF5)
find_package(yaml-cpp REQUIRED)          # target: yaml-cpp (no namespace in 0.7)
find_package(nlohmann_json 3 REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(CLI11 REQUIRED)

# --- per part -------------------------------------------------------------------------
if(SUITE_WITH_MPM2GRID)
  include(FindPETScPkgConfig)
  include(FindMETIS)
  find_package(OpenMP REQUIRED COMPONENTS CXX)  # GCC's libgomp: threads inside a rank
endif()
if(SUITE_WITH_MPM2GRID OR SUITE_WITH_CARVING OR SUITE_WITH_FOAM_EROSION_FEM OR SUITE_WITH_STUDIES)
  find_package(Eigen3 3.3 REQUIRED NO_MODULE)
endif()
if(SUITE_WITH_CARVING)
  find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs calib3d)
  find_package(PNG REQUIRED)  # libpng: seed images read and written without imgcodecs (carving/image/png_codec.hpp)
endif()
if(SUITE_WITH_RICE)
  # ml: the random forest and SVM of the ASV classifiers; dnn: a user's ONNX network (libopencv-ml-dev and
  # libopencv-dnn-dev, both pulled in by libopencv-dev)
  find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs ml dnn)
  # libtorch (libtorch-dev, CPU): trains and runs the convolutional network on grain crops (rice/cnn/)
  find_package(Torch REQUIRED)
  # libonnx (libonnx-dev): reads a user's ONNX network to replace what OpenCV 4.6 cannot import (onnx_graph.hpp)
  find_package(ONNX REQUIRED)
endif()
if(SUITE_WITH_STUDIES)
  find_package(OpenTURNS REQUIRED)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(MUPARSER REQUIRED IMPORTED_TARGET muparser)
endif()
if(SUITE_WITH_FOAM_EROSION_FEM)
  # Debian's openfoam package puts its solvers on PATH; the tests run the real programs.
  find_program(SUITE_INTERFOAM interFoam REQUIRED)
  find_program(SUITE_BLOCKMESH blockMesh REQUIRED)
endif()

# --- tests and benchmarks ----------------------------------------------------------------
if(SUITE_BUILD_TESTS)
  find_package(GTest REQUIRED)
  # Debian's python3 sees python3-numpy/-h5py/-matplotlib; a pyenv python3 first on PATH does not.
  set(SUITE_PYTHON /usr/bin/python3 CACHE FILEPATH "python3 with numpy, h5py and matplotlib (tests and charts)")
  set(Python3_EXECUTABLE ${SUITE_PYTHON})
  find_package(Python3 3.9 REQUIRED COMPONENTS Interpreter)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c "import numpy, h5py, matplotlib"
                  RESULT_VARIABLE py_rc ERROR_VARIABLE py_err OUTPUT_QUIET)
  if(NOT py_rc EQUAL 0)
    message(FATAL_ERROR "${Python3_EXECUTABLE} cannot import numpy, h5py and matplotlib (${py_err}). "
                        "Install python3-numpy python3-h5py python3-matplotlib (./suite setup), "
                        "or point -DSUITE_PYTHON at a python3 that has them.")
  endif()
endif()
if(SUITE_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
