#pragma once
// The message of the InvalidInput that f throws, "not InvalidInput: ..." for any other exception,
// or "no error": for tests that assert what a refusal says.
#include <exception>
#include <string>

#include "volspline/core/error.h"

namespace volspline::test_support {

template <class F>
std::string invalid_input_message(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not InvalidInput: ") + e.what();
  }
  return "no error";
}

}  // namespace volspline::test_support
