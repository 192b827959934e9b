# The viewer script of interactive pages (docs/web-pages.md): web/src/viewer.js and the parts of
# three.js it imports, bundled by esbuild (web/build-viewer.mjs) and embedded in the library as a
# generated source, so an installed volspline writes pages without node_modules. Where node,
# three or esbuild are missing (scripts/install-web-deps installs them), the generated source
# holds an empty script and the reason, and `--html` exits 2 saying so.
set(VOLSPLINE_WEB_DIR ${PROJECT_SOURCE_DIR}/web)
set(volspline_web_generated ${PROJECT_BINARY_DIR}/generated/web_viewer_script.cpp)
find_program(VOLSPLINE_NODE node)
set(volspline_web_missing "")
if(NOT VOLSPLINE_NODE)
  set(volspline_web_missing "node was not found when it was built")
elseif(NOT EXISTS ${VOLSPLINE_WEB_DIR}/node_modules/three/package.json OR NOT EXISTS ${VOLSPLINE_WEB_DIR}/node_modules/esbuild/package.json)
  set(volspline_web_missing "three.js and esbuild were not installed in web/node_modules when it was built")
endif()
# A later `npm ci` (scripts/install-web-deps) reconfigures, so that the viewer is built then.
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${VOLSPLINE_WEB_DIR}/package-lock.json)
if(EXISTS ${VOLSPLINE_WEB_DIR}/node_modules/.package-lock.json)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${VOLSPLINE_WEB_DIR}/node_modules/.package-lock.json)
endif()
if(volspline_web_missing STREQUAL "")
  set(volspline_web_bundle ${PROJECT_BINARY_DIR}/generated/web_viewer.js)
  add_custom_command(OUTPUT ${volspline_web_bundle}
    COMMAND ${VOLSPLINE_NODE} ${VOLSPLINE_WEB_DIR}/build-viewer.mjs ${volspline_web_bundle}
    DEPENDS ${VOLSPLINE_WEB_DIR}/src/viewer.js ${VOLSPLINE_WEB_DIR}/build-viewer.mjs ${VOLSPLINE_WEB_DIR}/package-lock.json
    COMMENT "Bundling the interactive page viewer (three.js, esbuild)" VERBATIM)
  add_custom_command(OUTPUT ${volspline_web_generated}
    COMMAND ${CMAKE_COMMAND} -DBUNDLE=${volspline_web_bundle} -DOUTPUT=${volspline_web_generated} -P ${PROJECT_SOURCE_DIR}/cmake/embed_web_viewer.cmake
    DEPENDS ${volspline_web_bundle} ${PROJECT_SOURCE_DIR}/cmake/embed_web_viewer.cmake
    COMMENT "Embedding the interactive page viewer" VERBATIM)
else()
  message(STATUS "volspline: interactive pages (--html) disabled: ${volspline_web_missing}")
  execute_process(COMMAND ${CMAKE_COMMAND} "-DMISSING=${volspline_web_missing}" -DOUTPUT=${volspline_web_generated}
    -P ${PROJECT_SOURCE_DIR}/cmake/embed_web_viewer.cmake)
endif()
# Interactive pages (src/web/) hold their scene as JSON: they belong to the models component.
if(TARGET volspline_models)
  target_sources(volspline_models PRIVATE ${volspline_web_generated})
endif()
# Half a megabyte of string literals: compiled on its own, not in a unity batch.
set_source_files_properties(${volspline_web_generated} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON
  INCLUDE_DIRECTORIES ${PROJECT_SOURCE_DIR}/src/web)
