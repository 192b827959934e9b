#pragma once
// The viewer script of interactive pages: web/src/viewer.js with three.js, bundled and minified
// by esbuild when volspline is built (cmake/web_viewer.cmake generates the definitions from
// web/node_modules; docs/web-pages.md).
#include <string_view>

namespace volspline {

/// The script, ASCII, free of "</script" and "<!--"; empty where three.js or esbuild was not
/// installed when this volspline was built.
std::string_view web_viewer_script();

/// Why web_viewer_script() is empty, and what to do about it; empty when it is not.
std::string_view web_viewer_missing_reason();

}  // namespace volspline
