# The library as components (docs/design.md "Components", docs/using-volspline.md), each a
# target of its own so that the core builds with Eigen and oneTBB alone:
#
#   volspline::core    core/ spline/ construct/ analysis/ boxspline/, triangle meshes, the
#                      tensor-product extraction, colour maps and pictures in memory, volume data
#                      parsers. Eigen 3 and oneTBB; with VOLSPLINE_WITH_STB also PNG output, text
#                      labels and colour bars (stb), with VOLSPLINE_WITH_GLTF .glb output
#                      (tinygltf); without them PNG and .glb are refused with a message.
#   volspline::cgal    CGAL's exact geometry: simplex splines, tetrahedral meshes (orientation,
#                      Delaunay, Mesh_3), the exact trimming of swept envelopes.
#   volspline::models  model and scene files, free-form deformation, pipeline/: nlohmann-json and
#                      pugixml; needs volspline::cgal, because a model may hold a simplex spline
#                      volume and reading one validates it exactly.
#   volspline::vtk     the VTU/VTK readers of tetrahedral meshes and volume data (VTK 9).
#   volspline::render  the Embree ray caster (and, with models, `view`'s picture pipeline).
#   volspline::volspline  every component this build has (an interface target).
#
# A component's sources are named below by path (VOLSPLINE_COMPONENT_RULES); the core is what is
# left over, so a new file lands in the core unless its layer or name is listed there.
# .ci/core-only (a CI stage) builds, installs and uses the core with nothing else to be found,
# and fails if a core object reads a header of an optional package.

option(VOLSPLINE_WITH_CGAL "Build volspline::cgal and volspline::models (CGAL, nlohmann-json, pugixml)" ON)
option(VOLSPLINE_WITH_VTK "Build volspline::vtk, the VTU/VTK readers (VTK 9; needs VOLSPLINE_WITH_CGAL)" ON)
option(VOLSPLINE_WITH_EMBREE "Build volspline::render, the ray caster (Embree 3)" ON)
option(VOLSPLINE_WITH_STB "PNG output, text labels and colour bars in volspline::core (stb; needed by cgal and render)" ON)
option(VOLSPLINE_WITH_GLTF "glTF (.glb) output of volspline::core (tinygltf)" ON)
if(VOLSPLINE_WITH_VTK AND NOT VOLSPLINE_WITH_CGAL)
  message(FATAL_ERROR "VOLSPLINE_WITH_VTK needs VOLSPLINE_WITH_CGAL: the tetrahedral meshes it reads are validated with CGAL's exact orientation")
endif()
if((VOLSPLINE_WITH_CGAL OR VOLSPLINE_WITH_EMBREE) AND NOT VOLSPLINE_WITH_STB)
  message(FATAL_ERROR "VOLSPLINE_WITH_CGAL and VOLSPLINE_WITH_EMBREE need VOLSPLINE_WITH_STB: X-ray pictures and renderings carry colour bars with text")
endif()
set(volspline_full ON)
foreach(part CGAL VTK EMBREE STB GLTF)
  if(NOT VOLSPLINE_WITH_${part})
    set(volspline_full OFF)
  endif()
endforeach()
foreach(program CLI TESTS BENCH PYTHON FUZZ)
  if(VOLSPLINE_BUILD_${program} AND NOT volspline_full)
    message(FATAL_ERROR "VOLSPLINE_BUILD_${program} needs every component (VOLSPLINE_WITH_CGAL, _VTK, _EMBREE, _STB, _GLTF): "
                        "turn it off for a partial build, e.g. -DVOLSPLINE_BUILD_CLI=OFF -DVOLSPLINE_BUILD_TESTS=OFF -DVOLSPLINE_BUILD_BENCH=OFF -DVOLSPLINE_BUILD_PYTHON=OFF")
  endif()
endforeach()

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
if(VOLSPLINE_WITH_STB)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)
endif()
if(VOLSPLINE_WITH_GLTF)
  # Debian's libtinygltf-dev ships the implementation as a shared library (libtinygltf.so), so no
  # source file defines TINYGLTF_IMPLEMENTATION.
  find_package(TinyGLTF REQUIRED)
endif()
if(VOLSPLINE_WITH_CGAL)
  # CGAL (header-only in 5.x; Debian's libcgal-dev brings GMP and MPFR): exact predicates and
  # constructions for the mesh arrangement that trims swept envelopes (extract/, docs/sweeps.md),
  # tetrahedral meshes and simplex splines.
  find_package(CGAL 5.5 REQUIRED)
  find_package(nlohmann_json 3.10 REQUIRED)
  find_package(pugixml REQUIRED)
endif()
if(VOLSPLINE_WITH_EMBREE)
  find_package(embree 3 REQUIRED)
endif()
if(VOLSPLINE_WITH_VTK)
  # VTK (libvtk9-dev): the readers of VTU and legacy VTK unstructured grids that a tetrahedral
  # domain may come from (mesh/tetrahedral_mesh_reader.h); private to the library like CGAL.
  set(VOLSPLINE_VTK_COMPONENTS CommonCore CommonDataModel CommonExecutionModel CommonMath IOXML IOLegacy IOImage)
  find_package(VTK 9 REQUIRED COMPONENTS ${VOLSPLINE_VTK_COMPONENTS})
  list(TRANSFORM VOLSPLINE_VTK_COMPONENTS PREPEND VTK:: OUTPUT_VARIABLE VOLSPLINE_VTK_TARGETS)
endif()

# Which source goes where: the first rule whose regular expression matches the path below src/
# names the component; what no rule matches is core. The same rules place the public headers
# (cmake/package.cmake installs those of the components built).
set(VOLSPLINE_COMPONENT_RULES
  "vtk=(io/volume_data_vtk|mesh/tetrahedral_mesh_reader)\\.cpp$"
  "render=(render/mesh_renderer|render/point_cloud_image|pipeline/solid_view_picture)\\.cpp$"
  "cgal=simplex/"
  "cgal=extract/simplex_"
  "cgal=extract/(superset_trimming|image_contouring|image_membership|sheet_refinement|swept_envelope|trimmed_solid_boundary)\\.cpp$"
  "cgal=mesh/(tetrahedral_mesh|tetrahedron_locator|longest_edge_bisection|delaunay_tetrahedralization|point_cloud_domain|surface_tetrahedralization|interface_split|material_interface|self_intersections)\\.cpp$"
  "cgal=render/xray_image\\.cpp$"
  "core=io/(atomic_file|volume_data|volume_data_inr|volume_data_ply)\\.cpp$"
  "models=(io|pipeline|deform|web)/"
  "models=boxspline/scene_file\\.cpp$"
  # Text labels (stb_easy_font) and the colour bars drawn with them: core with stb, else nowhere.
  "stb=render/(text|color_bar)\\.cpp$")
macro(volspline_split_rule rule)
  string(FIND "${rule}" "=" volspline_at)
  string(SUBSTRING "${rule}" 0 ${volspline_at} rule_component)
  math(EXPR volspline_at "${volspline_at} + 1")
  string(SUBSTRING "${rule}" ${volspline_at} -1 rule_regex)
endmacro()
function(volspline_component_of path out)
  foreach(rule ${VOLSPLINE_COMPONENT_RULES})
    volspline_split_rule("${rule}")
    if(path MATCHES "/src/${rule_regex}")
      set(${out} ${rule_component} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  set(${out} core PARENT_SCOPE)
endfunction()
# Rule by rule, so that each component's list (and so its unity batches) keeps one order.
file(GLOB_RECURSE volspline_left CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/*.cpp)
foreach(rule ${VOLSPLINE_COMPONENT_RULES})
  volspline_split_rule("${rule}")
  set(taken ${volspline_left})
  list(FILTER taken INCLUDE REGEX "/src/${rule_regex}")
  list(FILTER volspline_left EXCLUDE REGEX "/src/${rule_regex}")
  list(APPEND VOLSPLINE_${rule_component}_SOURCES ${taken})
endforeach()
list(APPEND VOLSPLINE_core_SOURCES ${volspline_left})
if(VOLSPLINE_WITH_STB)
  list(APPEND VOLSPLINE_core_SOURCES ${VOLSPLINE_stb_SOURCES})
endif()
# solid_view_picture (everything `volspline view` shows) reads models: it is part of render only
# when the model files are built.
if(NOT VOLSPLINE_WITH_CGAL)
  list(FILTER VOLSPLINE_render_SOURCES EXCLUDE REGEX "/pipeline/")
endif()

set(VOLSPLINE_COMPONENTS)
function(volspline_add_component name)
  add_library(volspline_${name} ${VOLSPLINE_${name}_SOURCES})
  add_library(volspline::${name} ALIAS volspline_${name})
  target_compile_options(volspline_${name} PRIVATE ${VOLSPLINE_SANITIZE_OPTIONS})
  target_compile_features(volspline_${name} PUBLIC cxx_std_20)
  target_include_directories(volspline_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  set_target_properties(volspline_${name} PROPERTIES EXPORT_NAME ${name}
    VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  if(VOLSPLINE_BUILD_PYTHON)
    # The Python module is one shared object, so the static libraries it holds must be position
    # independent.
    set_target_properties(volspline_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
  set(VOLSPLINE_COMPONENTS ${VOLSPLINE_COMPONENTS} ${name} PARENT_SCOPE)
endfunction()

configure_file(${PROJECT_SOURCE_DIR}/cmake/version.h.in ${PROJECT_BINARY_DIR}/include/volspline/core/version.h @ONLY)

volspline_add_component(core)
# Unity builds (Makefile, docs/design.md): spline_evaluation.cpp explicitly instantiates members of
# TensorSpline<D> that tensor_spline.cpp's `template class TensorSpline<D>` instantiates again;
# clang refuses the pair in one translation unit, so this file is compiled on its own.
set_source_files_properties(${PROJECT_SOURCE_DIR}/src/spline/spline_evaluation.cpp PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
target_link_libraries(volspline_core PUBLIC Eigen3::Eigen TBB::tbb)
if(VOLSPLINE_WITH_STB)
  target_link_libraries(volspline_core PRIVATE PkgConfig::STB)
  target_compile_definitions(volspline_core PRIVATE VOLSPLINE_WITH_STB=1)
endif()
if(VOLSPLINE_WITH_GLTF)
  target_link_libraries(volspline_core PRIVATE TinyGLTF::TinyGLTF)
  target_compile_definitions(volspline_core PRIVATE VOLSPLINE_WITH_GLTF=1)
endif()

if(VOLSPLINE_WITH_CGAL)
  volspline_add_component(cgal)
  target_link_libraries(volspline_cgal PUBLIC volspline_core PRIVATE CGAL::CGAL)
  # CGAL's oneTBB support: the self-intersection check of a trimmed boundary runs with
  # CGAL::Parallel_if_available_tag (every other CGAL call here keeps its sequential default).
  # The definition that CGAL::TBB_support would carry, set privately so that the installed
  # package does not need that target; oneTBB itself comes with volspline::core.
  target_compile_definitions(volspline_cgal PRIVATE CGAL_LINKED_WITH_TBB)
endif()
if(VOLSPLINE_WITH_VTK)
  volspline_add_component(vtk)
  target_link_libraries(volspline_vtk PUBLIC volspline_cgal PRIVATE ${VOLSPLINE_VTK_TARGETS})
endif()
if(VOLSPLINE_WITH_CGAL)
  volspline_add_component(models)
  target_link_libraries(volspline_models PUBLIC volspline_cgal nlohmann_json::nlohmann_json PRIVATE pugixml::pugixml)
  if(VOLSPLINE_WITH_VTK)
    # read_volume_data hands .vtu/.vti/.vtk/.nii to the VTK readers, or refuses them by name.
    target_link_libraries(volspline_models PRIVATE volspline_vtk)
    target_compile_definitions(volspline_models PRIVATE VOLSPLINE_WITH_VTK=1)
  endif()
endif()
if(VOLSPLINE_WITH_EMBREE)
  volspline_add_component(render)
  target_link_libraries(volspline_render PUBLIC volspline_core PRIVATE embree)
  if(VOLSPLINE_WITH_CGAL)
    target_link_libraries(volspline_render PUBLIC volspline_models)
  endif()
endif()

add_library(volspline INTERFACE)
add_library(volspline::volspline ALIAS volspline)
foreach(component ${VOLSPLINE_COMPONENTS})
  target_link_libraries(volspline INTERFACE volspline_${component})
endforeach()
message(STATUS "volspline components: ${VOLSPLINE_COMPONENTS}")
