# Installation and the package files (docs/using-volspline.md): `cmake --install` puts the
# headers, the library, the command line, a CMake package (find_package(volspline CONFIG)) and a
# pkg-config file under the prefix; the build tree holds a package of its own, so a project can
# point volspline_DIR at a build folder without installing.
include(CMakePackageConfigHelpers)

set(VOLSPLINE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/volspline)
# The exported targets: volspline::<component> for every component built, and volspline::volspline
# linking them all (cmake/library.cmake).
set(VOLSPLINE_EXPORTED_TARGETS volspline)
foreach(component ${VOLSPLINE_COMPONENTS})
  list(APPEND VOLSPLINE_EXPORTED_TARGETS volspline_${component})
endforeach()

# 0.x: a minor version may change the interface, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/volsplineConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
if(NOT BUILD_SHARED_LIBS)
  set(BUILD_SHARED_LIBS OFF)
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/volsplineConfig.cmake.in ${PROJECT_BINARY_DIR}/volsplineConfig.cmake @ONLY)
export(TARGETS ${VOLSPLINE_EXPORTED_TARGETS} NAMESPACE volspline:: FILE ${PROJECT_BINARY_DIR}/volsplineTargets.cmake)

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
set(volspline_pc_files)
if(VOLSPLINE_WITH_EMBREE)
  list(APPEND volspline_pc_files embree)
endif()
# CommonExecutionModel: the readers call vtkAlgorithm directly, which the IO libraries only link.
if(VOLSPLINE_WITH_VTK)
  list(APPEND volspline_pc_files ${VOLSPLINE_VTK_TARGETS})
endif()
foreach(dependency ${volspline_pc_files})
  volspline_link_files(${dependency} files)
  list(APPEND VOLSPLINE_PC_PRIVATE_LIBS ${files})
endforeach()
list(JOIN VOLSPLINE_PC_PRIVATE_LIBS " " VOLSPLINE_PC_PRIVATE_LIBS)
# The components, each before the ones it needs (render, models, vtk, cgal, core), and what
# pkg-config knows of their dependencies.
set(VOLSPLINE_PC_LIBS)
foreach(component ${VOLSPLINE_COMPONENTS})
  list(PREPEND VOLSPLINE_PC_LIBS -lvolspline_${component})
endforeach()
list(JOIN VOLSPLINE_PC_LIBS " " VOLSPLINE_PC_LIBS)
set(VOLSPLINE_PC_REQUIRES eigen3 tbb)
set(VOLSPLINE_PC_REQUIRES_PRIVATE)
if(VOLSPLINE_WITH_CGAL)
  list(APPEND VOLSPLINE_PC_REQUIRES nlohmann_json)
  list(APPEND VOLSPLINE_PC_REQUIRES_PRIVATE pugixml gmpxx mpfr gmp)
endif()
if(VOLSPLINE_WITH_STB)
  list(APPEND VOLSPLINE_PC_REQUIRES_PRIVATE stb)
endif()
if(VOLSPLINE_WITH_GLTF)
  list(APPEND VOLSPLINE_PC_REQUIRES_PRIVATE tinygltf)
endif()
list(JOIN VOLSPLINE_COMPONENTS " " VOLSPLINE_PC_COMPONENTS)
list(JOIN VOLSPLINE_PC_REQUIRES " " VOLSPLINE_PC_REQUIRES)
list(JOIN VOLSPLINE_PC_REQUIRES_PRIVATE " " VOLSPLINE_PC_REQUIRES_PRIVATE)
file(RELATIVE_PATH VOLSPLINE_PC_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" VOLSPLINE_PC_PREFIX "${VOLSPLINE_PC_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/volspline.pc.in ${PROJECT_BINARY_DIR}/volspline.pc @ONLY)

if(VOLSPLINE_INSTALL)
  install(TARGETS ${VOLSPLINE_EXPORTED_TARGETS} EXPORT volsplineTargets
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
