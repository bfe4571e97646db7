# Shared helpers for dynslam targets.

# Warnings: -Wall -Wextra -Wpedantic, kept clean; -Winvalid-pch reports a translation unit
# that cannot use its precompiled header (e.g. flags that differ from the shared one's).
function(dynslam_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Winvalid-pch)
endfunction()

# dynslam_add_library(NAME <name> SOURCES ... [MRPT_PCH] [EXPORT_SET <set>] LIBS ...)
# Creates dynslam_<name> (alias dynslam::<name>), public headers in libs/<name>/include.
# EXPORT_SET: the installed export set (default dynslamTargets; dynslam::apps has its own,
# loaded by dynslamConfig.cmake only with OpenCV's videoio, doc/building.md).
function(dynslam_add_library)
  cmake_parse_arguments(A "MRPT_PCH" "NAME;EXPORT_SET" "SOURCES;LIBS" ${ARGN})
  if(NOT A_EXPORT_SET)
    set(A_EXPORT_SET dynslamTargets)
  endif()
  set(t dynslam_${A_NAME})
  add_library(${t} ${A_SOURCES})
  add_library(dynslam::${A_NAME} ALIAS ${t})
  # DEFINE_SYMBOL "": no -Ddynslam_<name>_EXPORTS in a shared build (nothing uses it; all
  # symbols have default visibility), so a static and a shared build compile every source with
  # the same command line and share ccache's entries (tests/consumer: SharedLibsInstall).
  set_target_properties(${t} PROPERTIES EXPORT_NAME ${A_NAME} DEFINE_SYMBOL "")
  target_include_directories(${t} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${t} PUBLIC ${A_LIBS})
  target_compile_features(${t} PUBLIC cxx_std_17)
  dynslam_warnings(${t})
  if(A_MRPT_PCH)
    dynslam_mrpt_pch(${t})
  endif()
  install(TARGETS ${t} EXPORT ${A_EXPORT_SET}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# The shared precompiled MRPT header (target dynslam_mrpt_pch, libs/pch): reused, not rebuilt,
# by every library that asks for it. Same compile flags as the PCH target is a requirement of
# the compiler; per-source COMPILE_DEFINITIONS are fine on SKIP_PRECOMPILE_HEADERS sources.
function(dynslam_mrpt_pch target)
  if(NOT TARGET dynslam_mrpt_pch)
    message(FATAL_ERROR "dynslam_mrpt_pch(${target}): libs/pch must be added first")
  endif()
  target_precompile_headers(${target} REUSE_FROM dynslam_mrpt_pch)
endfunction()

# TCLAP as bundled with MRPT (header-only), for command lines. Build-tree only: it is not part
# of the link interface of installed targets (dynslamConfig.cmake does not look for it, and
# nothing of it is needed to link a static dynslam library).
function(dynslam_link_tclap target)
  if(NOT TARGET mrpt::tclap)
    find_package(mrpt-tclap REQUIRED)
  endif()
  target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:mrpt::tclap>)
endfunction()

# dynslam_add_app(NAME <exe> SOURCES ... LIBS ...)
function(dynslam_add_app)
  cmake_parse_arguments(A "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${A_NAME} ${A_SOURCES})
  target_link_libraries(${A_NAME} PRIVATE ${A_LIBS})
  dynslam_warnings(${A_NAME})
  install(TARGETS ${A_NAME} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
