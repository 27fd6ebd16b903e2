# The installed libraries as another project sees them (ctest -L install; tests/CMakeLists.txt):
#   1. cmake --install <build> --component development --prefix <work>/prefix
#   2. configure and build examples/cpp as a separate project against that prefix only
#      (CMAKE_PREFIX_PATH), with the build's generator, compiler and build type;
#   3. run the example and require the PSNR line of its Wiener decode.
# Run as: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -DMAKE_PROGRAM=...
#               -DCXX_COMPILER=... -DBUILD_TYPE=... -DLAUNCHER=... -P run.cmake
# The development component only: the Python module (component python) need not be built for
# this test to run.
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run.cmake: -D${var}=... is required")
  endif()
endforeach()

# step(<what> <command...>): runs the command, its output in the log; fails the test naming it.
function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
set(example_build ${WORK_DIR}/example)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

step("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --component development --prefix ${prefix})
foreach(f include/pinmask/pinmask.hpp include/pinmask/core/fft/fft.hpp include/pinmask/core/version.hpp
          include/pinmask/decode/depthmap/depthmap.hpp)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "install: ${prefix}/${f} is missing")
  endif()
endforeach()
file(GLOB_RECURSE config_files ${prefix}/*/pinmaskConfig.cmake)
if(NOT config_files)
  message(FATAL_ERROR "install: no pinmaskConfig.cmake under ${prefix}")
endif()

set(configure_args -S ${SOURCE_DIR}/examples/cpp -B ${example_build} -G ${GENERATOR}
                   -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix})
if(MAKE_PROGRAM)
  list(APPEND configure_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(BUILD_TYPE)
  list(APPEND configure_args -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
endif()
if(LAUNCHER)
  list(APPEND configure_args -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
step("configure examples/cpp" ${CMAKE_COMMAND} ${configure_args})
step("build examples/cpp" ${CMAKE_COMMAND} --build ${example_build})

step("run the example" ${example_build}/pinmask_example)
message("${step_output}")
if(NOT step_output MATCHES "Wiener \\(NSR [^)]+\\): PSNR (-?[0-9]+\\.[0-9]+) dB")
  message(FATAL_ERROR "the example did not print the Wiener decode's PSNR")
endif()
