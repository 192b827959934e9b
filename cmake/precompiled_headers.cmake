# Precompiled headers (CMake's target_precompile_headers): the heavy headers a target's unity
# batches all parse (Eigen, CGAL's kernel, GoogleTest, nlohmann-json, CLI11, pybind11) are parsed
# once per target instead of once per batch. CI builds three times from clean (Release, ASan,
# fuzz), so this is CI time (docs/testing.md). Only packages the target already uses are named,
# so volspline::core still reads no optional package's header (.ci/core-only checks).
option(VOLSPLINE_PRECOMPILED_HEADERS "Precompile the heavy headers of each target" ON)

function(volspline_precompile target)
  if(VOLSPLINE_PRECOMPILED_HEADERS AND TARGET ${target})
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
