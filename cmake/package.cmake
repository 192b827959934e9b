# Installation and the package files (docs/using-volspline.md): `cmake --install` puts the
# headers, the library, the command line, a CMake package (find_package(volspline CONFIG)) and a
# pkg-config file under the prefix; the build tree holds a package of its own, so a project can
# point volspline_DIR at a build folder without installing.
include(CMakePackageConfigHelpers)

set(VOLSPLINE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/volspline)
set_target_properties(volspline PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})

# 0.x: a minor version may change the interface, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/volsplineConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
if(NOT BUILD_SHARED_LIBS)
  set(BUILD_SHARED_LIBS OFF)
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/volsplineConfig.cmake.in ${PROJECT_BINARY_DIR}/volsplineConfig.cmake @ONLY)
export(TARGETS volspline NAMESPACE volspline:: FILE ${PROJECT_BINARY_DIR}/volsplineTargets.cmake)

# pkg-config cannot name VTK or Embree (neither ships a .pc file), so a static library's private
# link line lists their files as CMake found them.
function(volspline_link_files target out)
  set(files)
  get_target_property(type ${target} TYPE)
  get_target_property(imported ${target} IMPORTED)
  if(imported AND NOT type STREQUAL "INTERFACE_LIBRARY")
    get_target_property(location ${target} IMPORTED_LOCATION_RELEASE)
    if(NOT location)
      get_target_property(location ${target} IMPORTED_LOCATION)
    endif()
    if(NOT location)
      get_target_property(configurations ${target} IMPORTED_CONFIGURATIONS)
      list(GET configurations 0 first)
      get_target_property(location ${target} IMPORTED_LOCATION_${first})
    endif()
    if(location)
      list(APPEND files ${location})
    endif()
  endif()
  set(${out} ${files} PARENT_SCOPE)
endfunction()
set(VOLSPLINE_PC_PRIVATE_LIBS)
# CommonExecutionModel: the readers call vtkAlgorithm directly, which the IO libraries only link.
foreach(dependency embree VTK::CommonCore VTK::CommonDataModel VTK::CommonExecutionModel VTK::CommonMath VTK::IOXML VTK::IOLegacy VTK::IOImage)
  volspline_link_files(${dependency} files)
  list(APPEND VOLSPLINE_PC_PRIVATE_LIBS ${files})
endforeach()
list(JOIN VOLSPLINE_PC_PRIVATE_LIBS " " VOLSPLINE_PC_PRIVATE_LIBS)
file(RELATIVE_PATH VOLSPLINE_PC_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" VOLSPLINE_PC_PREFIX "${VOLSPLINE_PC_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/volspline.pc.in ${PROJECT_BINARY_DIR}/volspline.pc @ONLY)

if(VOLSPLINE_INSTALL)
  install(TARGETS volspline EXPORT volsplineTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/volspline ${PROJECT_BINARY_DIR}/include/volspline
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  if(VOLSPLINE_BUILD_CLI)
    install(TARGETS volspline_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
  install(EXPORT volsplineTargets NAMESPACE volspline:: DESTINATION ${VOLSPLINE_CMAKE_DIR})
  install(FILES ${PROJECT_BINARY_DIR}/volsplineConfig.cmake ${PROJECT_BINARY_DIR}/volsplineConfigVersion.cmake
    DESTINATION ${VOLSPLINE_CMAKE_DIR})
  install(FILES ${PROJECT_BINARY_DIR}/volspline.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endif()
