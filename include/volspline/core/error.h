#pragma once
// Errors that cross the library boundary. The command line maps InvalidInput and IoError to
// exit code 2 (bad input or usage: a file the user named that cannot be read or written is the
// user's to fix) and every other Error to exit code 1 (internal failure).
#include <stdexcept>
#include <string>

namespace volspline {

/// Base of every exception volspline throws.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Input that does not describe a valid object: a malformed model, a parameter outside the
/// domain, inconsistent sizes. `where()` locates the problem (a JSON path such as
/// `objects[0].knots[1][3]`, a line number, or empty); `message()` says what was expected.
class InvalidInput : public Error {
 public:
  explicit InvalidInput(std::string message, std::string where = {});
  const std::string& where() const noexcept { return where_; }
  const std::string& message() const noexcept { return message_; }
  /// The same error located one level further out: `prefix` is prepended to `where()`
  /// (for example "objects[0].knots[1]" + "[3]").
  InvalidInput located(const std::string& prefix) const;

 private:
  std::string message_;
  std::string where_;
};

/// A file that cannot be opened, read or written (the CLI exits with code 2).
class IoError : public Error {
 public:
  using Error::Error;
};

/// An iterative method that did not reach its tolerance within its budget.
class NotConverged : public Error {
 public:
  using Error::Error;
};

}  // namespace volspline
