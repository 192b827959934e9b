#pragma once
// VTK's readers report problems as ErrorEvents (and print them unless observed). The tetrahedral
// mesh reader (mesh/) and the volume data reader (io/) attach this collector to a reader and turn
// the first error into an InvalidInput that names the file; warnings are observed only so that
// VTK does not print them.
#include <cctype>
#include <string>

#include <vtkCommand.h>
#include <vtkObject.h>

namespace volspline::detail {

struct VtkErrors {
  std::string first;
  static void collect(vtkObject*, unsigned long event, void* client, void* call) {
    auto* self = static_cast<VtkErrors*>(client);
    if (event == vtkCommand::ErrorEvent && self->first.empty() && call) self->first = static_cast<const char*>(call);
  }
};

/// A VTK message without its "ERROR: In FILE, line N\nvtkClass (0x...): " prefix.
inline std::string vtk_message_text(std::string message) {
  const auto colon = message.find("): ");
  if (colon != std::string::npos) message = message.substr(colon + 3);
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  return message;
}

}  // namespace volspline::detail
