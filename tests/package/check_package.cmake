# Uses volspline from outside, the three ways docs/using-volspline.md describes (ctest runs this
# script, tests/CMakeLists.txt: Package.*):
#  1. `cmake --install` into a fresh prefix, then examples/consumer finds the package there,
#     builds and runs (its checks: the ball's sphere face to 1e-12, the box's certified Jacobian);
#  2. the same consumer built from the pkg-config file alone;
#  1b. find_package(volspline COMPONENTS ...) gives the targets built and refuses one that was not;
#  3. a parent project that adds the source tree with add_subdirectory, next to a src/ folder of
#     its own whose file must not be compiled (the glob once used CMAKE_SOURCE_DIR).
# Arguments: -DSOURCE=<volspline source> -DBUILD=<its build folder> -DWORK=<scratch folder>
#            -DGENERATOR=<CMake generator> -DCXX=<C++ compiler>
foreach(variable SOURCE BUILD WORK GENERATOR CXX)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "check_package.cmake: -D${variable}=... is missing")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(prefix ${WORK}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "${what} failed (${code}):\n${out}\n${err}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

run("install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(file include/volspline/core/version.h include/volspline/spline/tensor_spline.h bin/volspline)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "install: ${prefix}/${file} is missing")
  endif()
endforeach()
file(GLOB_RECURSE config_files ${prefix}/*/volsplineConfig.cmake)
file(GLOB_RECURSE pc_files ${prefix}/*/volspline.pc)
if(NOT config_files OR NOT pc_files)
  message(FATAL_ERROR "install: no volsplineConfig.cmake or volspline.pc under ${prefix}")
endif()

# The installed command line says the project's version.
file(STRINGS ${SOURCE}/CMakeLists.txt project_line REGEX "^project\\(volspline VERSION")
string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" version "${project_line}")
run("volspline --version" ${prefix}/bin/volspline --version)
if(NOT output MATCHES "volspline ${version}")
  message(FATAL_ERROR "volspline --version printed '${output}', expected 'volspline ${version}'")
endif()

# 1. find_package from the installed prefix.
run("configure the consumer" ${CMAKE_COMMAND} -S ${SOURCE}/examples/consumer -B ${WORK}/consumer -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix})
run("build the consumer" ${CMAKE_COMMAND} --build ${WORK}/consumer)
run("run the consumer" ${WORK}/consumer/volspline_consumer)
if(NOT output MATCHES "volspline ${version}: sphere distance")
  message(FATAL_ERROR "the consumer printed '${output}'")
endif()

# 1b. Components: asking for those built gives their targets; asking for one that was not built
# fails and names it (cmake/volsplineConfig.cmake.in).
file(WRITE ${WORK}/components/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(components LANGUAGES CXX)
string(REPLACE \",\" \";\" wanted \"\${WANTED}\")
find_package(volspline CONFIG REQUIRED COMPONENTS \${wanted})
foreach(component \${wanted})
  if(NOT TARGET volspline::\${component})
    message(FATAL_ERROR \"no target volspline::\${component}\")
  endif()
endforeach()
")
run("find_package(volspline COMPONENTS ...)" ${CMAKE_COMMAND} -S ${WORK}/components -B ${WORK}/components-built -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix} -DWANTED=core,cgal,models,vtk,render)
execute_process(COMMAND ${CMAKE_COMMAND} -S ${WORK}/components -B ${WORK}/components-missing -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix} -DWANTED=core,imaginary
  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(code EQUAL 0 OR NOT "${out}${err}" MATCHES "built without the component imaginary")
  message(FATAL_ERROR "find_package(volspline COMPONENTS imaginary) did not fail naming the component (${code}):\n${out}\n${err}")
endif()

# 2. pkg-config, static.
get_filename_component(pc_dir ${pc_files} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
run("pkg-config" pkg-config --cflags --libs --static volspline)
string(STRIP "${output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run("build the consumer with pkg-config" ${CXX} -O1 ${SOURCE}/examples/consumer/consumer.cpp -o ${WORK}/pc_consumer ${flags})
run("run the pkg-config consumer" ${WORK}/pc_consumer)

# 3. add_subdirectory into a parent with its own src/.
file(MAKE_DIRECTORY ${WORK}/parent/src)
file(WRITE ${WORK}/parent/src/parent_only.cpp "#error the parent's own source must not reach volspline's library\n")
file(WRITE ${WORK}/parent/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(parent LANGUAGES CXX)
add_subdirectory(${SOURCE} volspline)
add_executable(parent_app ${SOURCE}/examples/consumer/consumer.cpp)
target_link_libraries(parent_app PRIVATE volspline::volspline)
if(TARGET volspline_tests OR TARGET volspline_cli)
  message(FATAL_ERROR \"tests are off in a parent project by default, and the command line was turned off\")
endif()
foreach(component core cgal models vtk render)
  get_target_property(sources volspline_\${component} SOURCES)
  foreach(source \${sources})
    if(source MATCHES \"parent_only\")
      message(FATAL_ERROR \"volspline's library took the parent's \${source}\")
    endif()
  endforeach()
endforeach()
")
run("configure the parent project" ${CMAKE_COMMAND} -S ${WORK}/parent -B ${WORK}/parent-build -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DVOLSPLINE_BUILD_CLI=OFF)
message(STATUS "package checks passed: install, find_package, pkg-config, add_subdirectory")
