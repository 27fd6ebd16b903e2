# Compile time: precompiled headers, and the optimisation level of the command line's units.
#
# Every translation unit of pinmask parses the same standard library and
# Eigen headers (about 2.5 s each on the CI machine's cores before any of our code), the command
# line's units also nlohmann-json and CLI11 (another 5.5 s). Each target compiles those once into
# a precompiled header (PRIVATE: nothing of it reaches an installed consumer) and every unit of
# the target starts from it. A unit still includes what it uses; the precompiled header only
# makes the parse free. PINMASK_PCH=OFF builds without them (to check that includes are
# complete: a missing include compiles with the header and fails without it).
option(PINMASK_PCH "Precompile the standard, Eigen, JSON and CLI11 headers per target" ON)

set(PINMASK_PCH_BASE
    <algorithm> <array> <cmath> <complex> <cstddef> <cstdint> <filesystem> <functional>
    <limits> <map> <memory> <optional> <sstream> <stdexcept> <string> <string_view> <utility>
    <vector> <Eigen/Core>)

# pinmask_precompile(<target> [JSON] [CLI] [PYBIND] [DOCTEST]): the base set, plus
# nlohmann/json (io/ and the faces), CLI11 (the command line), pybind11 (the module), doctest.
function(pinmask_precompile target)
  if(NOT PINMASK_PCH)
    return()
  endif()
  cmake_parse_arguments(P "JSON;CLI;PYBIND;DOCTEST" "" "" ${ARGN})
  set(headers ${PINMASK_PCH_BASE})
  if(P_JSON)
    list(APPEND headers <nlohmann/json.hpp>)
  endif()
  if(P_CLI)
    list(APPEND headers <CLI/CLI.hpp>)
  endif()
  if(P_PYBIND)
    list(APPEND headers <pybind11/pybind11.h> <pybind11/numpy.h> <pybind11/stl.h>)
  endif()
  if(P_DOCTEST)
    list(APPEND headers <doctest/doctest.h>)
  endif()
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()

# -O1 for the command line's own units (cli/ and its tests): they parse flags and write files (the
# numerical work is in the libraries, -O3), and CLI11's and nlohmann-json's templates take a
# third less time to compile at -O1. Floating-point results do not depend on the level (no
# fast-math, no contraction).
set(PINMASK_CLI_OPT $<$<OR:$<CONFIG:Release>,$<CONFIG:RelWithDebInfo>>:-O1>)
