# Compiler launcher, warnings and sanitizers shared by every target of the suite.

find_program(SUITE_CCACHE ccache)
if(SUITE_CCACHE)
  set(CMAKE_C_COMPILER_LAUNCHER ${SUITE_CCACHE})
  set(CMAKE_CXX_COMPILER_LAUNCHER ${SUITE_CCACHE})
  message(STATUS "ccache: ${SUITE_CCACHE}")
endif()

# suite_warnings(target): -Wall -Wextra and a few more that catch real bugs in numeric code.
add_library(suite_warnings INTERFACE)
target_compile_options(suite_warnings INTERFACE
  $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wshadow=local -Wnon-virtual-dtor -Wold-style-cast
                            -Wimplicit-fallthrough -Wformat=2>)
option(SUITE_WERROR "treat warnings as errors" OFF)
if(SUITE_WERROR)
  target_compile_options(suite_warnings INTERFACE -Werror)
endif()

# SUITE_SANITIZE: e.g. "address,undefined" (the asan preset sets it).
set(SUITE_SANITIZE "" CACHE STRING "comma-separated -fsanitize= list")
if(SUITE_SANITIZE)
  add_compile_options(-fsanitize=${SUITE_SANITIZE} -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${SUITE_SANITIZE})
endif()
