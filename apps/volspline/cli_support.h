#pragma once
// Small helpers shared by the subcommands: argument lists, object selection, number printing.
#include <array>
#include <string>
#include <vector>

#include "volspline/io/model_file.h"

namespace volspline::cli {

/// Parses "A,B,C" into exactly `count` finite numbers. \throw InvalidInput naming `option`.
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& option);
/// Parses "A,B,C" into exactly `count` integers >= minimum. \throw InvalidInput naming `option`.
std::vector<int> parse_integers(const std::string& text, std::size_t count, int minimum, const std::string& option);
/// "u", "v", "w" (or "s" for the 4th) or "0".."3" to a direction index. \throw InvalidInput.
int parse_direction(const std::string& text, const std::string& option);
/// Number of parameters of an object (1, 2 or 3).
int parameter_count(const ModelObject& object);
/// Formats numbers with 17 significant digits separated by spaces.
std::string join_numbers(const double* values, std::size_t count);

}  // namespace volspline::cli
