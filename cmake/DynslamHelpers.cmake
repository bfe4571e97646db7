# Shared helpers for dynslam targets.

# Warnings: -Wall -Wextra -Wpedantic, kept clean.
function(dynslam_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
endfunction()

# dynslam_add_library(NAME <name> SOURCES ... [MRPT_PCH] LIBS ...)
# Creates dynslam_<name> (alias dynslam::<name>), public headers in libs/<name>/include.
function(dynslam_add_library)
  cmake_parse_arguments(A "MRPT_PCH" "NAME" "SOURCES;LIBS" ${ARGN})
  set(t dynslam_${A_NAME})
  add_library(${t} ${A_SOURCES})
  add_library(dynslam::${A_NAME} ALIAS ${t})
  set_target_properties(${t} PROPERTIES EXPORT_NAME ${A_NAME})
  target_include_directories(${t} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${t} PUBLIC ${A_LIBS})
  target_compile_features(${t} PUBLIC cxx_std_17)
  dynslam_warnings(${t})
  if(A_MRPT_PCH)
    dynslam_mrpt_pch(${t})
  endif()
  install(TARGETS ${t} EXPORT dynslamTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()

# Precompiled MRPT headers (the heavy part of every MRPT translation unit).
function(dynslam_mrpt_pch target)
  target_precompile_headers(${target} PRIVATE
    <mrpt/obs/CActionCollection.h>
    <mrpt/obs/CSensoryFrame.h>
    <mrpt/obs/CObservationBearingRange.h>
    <mrpt/obs/CActionRobotMovement2D.h>
    <mrpt/poses/CPose2D.h>
    <mrpt/poses/CPosePDFGaussian.h>
    <mrpt/config/CConfigFileBase.h>
    <mrpt/system/COutputLogger.h>
    <Eigen/Dense>)
endfunction()

# dynslam_add_app(NAME <exe> SOURCES ... LIBS ...)
function(dynslam_add_app)
  cmake_parse_arguments(A "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${A_NAME} ${A_SOURCES})
  target_link_libraries(${A_NAME} PRIVATE ${A_LIBS})
  dynslam_warnings(${A_NAME})
  install(TARGETS ${A_NAME} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()
