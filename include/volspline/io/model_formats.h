#pragma once
// The file formats a model can be read from and written to, in one table: the command line
// picks a reader and writer by file extension (or by name with --format) from here, so adding
// a format means adding a row. Conventions of each format: docs/formats.md.
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "volspline/io/model_file.h"

namespace volspline {

struct ModelFormat {
  /// Short name for --format: "json", "gismo", "irit", "vtu".
  const char* name;
  /// Extension with its dot, lower case: ".json", ".xml", ".itd", ".vtu".
  const char* extension;
  /// One line for help texts.
  const char* description;
  /// Parses file contents; the second argument names the source in messages.
  Model (*parse)(std::string_view text, const std::string& source_name);
  /// The file contents of a model.
  std::string (*text)(const Model& model);
};

/// Every format, model files (JSON) first.
std::span<const ModelFormat> model_formats();

/// The format whose extension `path` has (any letter case).
/// \throw InvalidInput naming the path and the known extensions otherwise.
/// `format_option` is the option the error message suggests for naming the format instead.
const ModelFormat& model_format_from_path(const std::filesystem::path& path, std::string_view format_option = "--format");

/// The format called `name` (a name such as "gismo", or an extension with or without its dot).
/// \throw InvalidInput listing the known names otherwise.
const ModelFormat& model_format_named(std::string_view name);

/// Reads a model in `format`, or in the format of the path's extension when `format` is empty.
/// \throw IoError if the file cannot be read, InvalidInput for an unknown format or a bad file.
Model read_model_file(const std::filesystem::path& path, std::string_view format = {});

/// Writes a model atomically in `format`, or in the format of the path's extension when
/// `format` is empty. \throw IoError, InvalidInput (unknown format, model the format cannot hold).
void write_model_file(const Model& model, const std::filesystem::path& path, std::string_view format = {});

}  // namespace volspline
