# Installing the libraries for other CMake projects (included by the top CMakeLists.txt):
#   cmake --install build --prefix P
# puts the static libraries in P/lib, the public headers of their folders under P/include/pinmask
# (the repository-rooted layout: "core/fft/fft.hpp", with pinmask.hpp at its top) and the package
# files in P/lib/cmake/pinmask, so a project does
#   find_package(pinmask CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE pinmask::pinmask)
# (examples/cpp/ is such a project; tests/install builds it against an installed tree).
# These files are the `development` component; the Python module is the `python` component
# (python/CMakeLists.txt, scripts/install-python), the executable the `cli` component
# (cli/CMakeLists.txt, scripts/install-cli). The MPI layer (optimize/search/mpi/) and the
# benchmarks (bench/) are not installed as libraries: no installed library needs them.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PINMASK_INSTALLED_MODULES core design decode layout formats export simulate metrics search
                              report io calibrate depthmap)
# The folders whose headers are installed: the areas and the infrastructure, each as it stands in
# the repository (the command's cli/, the benchmarks and the MPI layer are left out).
set(PINMASK_INSTALLED_FOLDERS core design decode export optimize report io)

# pinmask::pinmask, every installed library at once (in this tree: pinmask::pinmask too).
add_library(pinmask_libraries INTERFACE)
foreach(module ${PINMASK_INSTALLED_MODULES})
  target_link_libraries(pinmask_libraries INTERFACE pinmask_${module})
endforeach()
set_target_properties(pinmask_libraries PROPERTIES EXPORT_NAME pinmask)
add_library(pinmask::pinmask ALIAS pinmask_libraries)

set(PINMASK_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/pinmask)
set(PINMASK_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/pinmask)

set(pinmask_installed_targets pinmask_libraries)
foreach(module ${PINMASK_INSTALLED_MODULES})
  list(APPEND pinmask_installed_targets pinmask_${module})
endforeach()
install(TARGETS ${pinmask_installed_targets} EXPORT pinmaskTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT development)
foreach(folder ${PINMASK_INSTALLED_FOLDERS})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/
          DESTINATION ${PINMASK_INSTALL_INCLUDEDIR}/${folder} COMPONENT development
          FILES_MATCHING PATTERN "*.hpp"
          PATTERN "mpi" EXCLUDE)  # optimize/search/mpi/: the executable's MPI layer
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/pinmask.hpp DESTINATION ${PINMASK_INSTALL_INCLUDEDIR}
        COMPONENT development)
install(FILES ${PROJECT_BINARY_DIR}/generated/core/version.hpp
        DESTINATION ${PINMASK_INSTALL_INCLUDEDIR}/core COMPONENT development)

install(EXPORT pinmaskTargets NAMESPACE pinmask:: DESTINATION ${PINMASK_INSTALL_CMAKEDIR}
        FILE pinmaskTargets.cmake COMPONENT development)
# What pinmaskConfig.cmake finds for the exported link lines: the fftw3 threads libraries are
# recorded by path (core/CMakeLists.txt), every other dependency by its imported target.
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/pinmaskConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/pinmaskConfig.cmake
                              INSTALL_DESTINATION ${PINMASK_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pinmaskConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pinmaskConfig.cmake ${PROJECT_BINARY_DIR}/pinmaskConfigVersion.cmake
        DESTINATION ${PINMASK_INSTALL_CMAKEDIR} COMPONENT development)
