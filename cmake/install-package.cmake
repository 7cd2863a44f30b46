# cmake --install and the package config behind
#   find_package(stickslip CONFIG REQUIRED [COMPONENTS core precision io run study mpi])
# which gives the imported targets
#   stickslip::core  the simulation library (model, engines, statistics, sweep;
#                    no I/O: its interface has fmt, Threads and Random123 only)
#   stickslip::precision  local fits and peak finders (model-free), and the
#                    drivers above the sweep: peak_sweep, crn_slopes
#   stickslip::io    config, result files, journal, writers (toml++, netCDF)
#   stickslip::run   journaled runs (resume, shards, stop), runners, shard merging
#   stickslip::study the paper study: design, peak refinement, claims, figures, report, plot
#   stickslip::mpi   the MPI sweep backend, when it was built
# Each library has its own export set, so a consumer that asks only for
# `core` needs none of the I/O libraries on its machine.
#
# A library that an exported one links (even PRIVATE: a static library carries
# its link dependencies) must be exported too: add it to the table below, with
# the dependencies its consumers need in cmake/stickslip-config.cmake.in, and
# link build-only helpers such as stickslip_warnings as
# $<BUILD_INTERFACE:stickslip_warnings>.
include(CMakePackageConfigHelpers)

set(stickslip_config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/stickslip)

# component -> library target (the EXPORT_NAME gives stickslip::<component>)
set(stickslip_components core precision io run study)
set(stickslip_target_core stickslip_core)
set(stickslip_target_precision stickslip_precision)
set(stickslip_target_io stickslip_io)
set(stickslip_target_run stickslip_run)
set(stickslip_target_study stickslip_study)
if(TARGET stickslip_mpi)
  list(APPEND stickslip_components mpi)
  set(stickslip_target_mpi stickslip_mpi)
endif()

foreach(component IN LISTS stickslip_components)
  set(target ${stickslip_target_${component}})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${component})
  install(TARGETS ${target} EXPORT stickslip-${component}-targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT stickslip-${component}-targets NAMESPACE stickslip::
    DESTINATION ${stickslip_config_dir})
endforeach()

install(TARGETS stickslip RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

# Public headers: include/stickslip but its detail/ folder, the generated
# version header, and the MPI backend's header when it is built. detail/ is
# private to the build: the lane engine's interface with the sweep
# (fast_block.hpp, there because the lane tests include it too). The Highway
# kernels are a private header of the core, src/core/engines/fast_math_simd.hpp
# (Highway is linked PRIVATE, and a user need not have it). package.downstream
# checks that no installed header is under detail/, includes Highway or
# includes a header that is not installed, and that each compiles alone.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/stickslip
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  PATTERN "detail" EXCLUDE)
install(FILES ${PROJECT_BINARY_DIR}/generated/stickslip/version.hpp
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stickslip)
if(TARGET stickslip_mpi)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/backends/mpi/include/stickslip
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()

configure_package_config_file(cmake/stickslip-config.cmake.in
  ${PROJECT_BINARY_DIR}/stickslip-config.cmake
  INSTALL_DESTINATION ${stickslip_config_dir})
# 0.x: a minor release may change the API (semantic versioning), so 0.1.*
# satisfies find_package(stickslip 0.1) but 0.2 does not. From 1.0 on,
# SameMajorVersion is the right rule.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/stickslip-config-version.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/stickslip-config.cmake
  ${PROJECT_BINARY_DIR}/stickslip-config-version.cmake
  ${PROJECT_SOURCE_DIR}/cmake/FindRandom123.cmake
  DESTINATION ${stickslip_config_dir})
