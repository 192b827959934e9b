#pragma once
// VTK's readers report problems as ErrorEvents (and print them unless observed). The tetrahedral
// mesh reader (mesh/) and the volume data reader (io/) attach this collector to a reader and turn
// the first error into an InvalidInput that names the file; warnings are observed only so that
// VTK does not print them.
#include <cctype>
#include <string>
#include <type_traits>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkXMLReader.h>

namespace volspline::detail {

struct VtkErrors {
  std::string first;
  /// Warnings count as errors too: the legacy readers warn ("Error reading ascii data. Possible
  /// mismatch of datasize with declaration.") where values are missing and carry on with zeros.
  bool warnings_are_errors = false;
  static void collect(vtkObject*, unsigned long event, void* client, void* call) {
    auto* self = static_cast<VtkErrors*>(client);
    const bool counts = event == vtkCommand::ErrorEvent || (self->warnings_are_errors && event == vtkCommand::WarningEvent);
    if (counts && self->first.empty() && call) self->first = static_cast<const char*>(call);
  }
  VtkErrors() {
    observer->SetCallback(&VtkErrors::collect);
    observer->SetClientData(this);
  }
  VtkErrors(const VtkErrors&) = delete;
  VtkErrors& operator=(const VtkErrors&) = delete;
  /// Observes the reader's errors and warnings, its pipeline's (which reports the reader's failure
  /// once more, from its executive) and, for XML readers, those of the reader and the parser.
  template <class Reader>
  void watch(Reader& reader) {
    reader.AddObserver(vtkCommand::ErrorEvent, observer);
    reader.AddObserver(vtkCommand::WarningEvent, observer);
    reader.GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
    if constexpr (std::is_base_of_v<vtkXMLReader, Reader>) {
      reader.SetReaderErrorObserver(observer);
      reader.SetParserErrorObserver(observer);
    }
  }
  vtkNew<vtkCallbackCommand> observer;
};

/// A VTK message without its "ERROR: In FILE, line N\nvtkClass (0x...): " prefix.
inline std::string vtk_message_text(std::string message) {
  const auto colon = message.find("): ");
  if (colon != std::string::npos) message = message.substr(colon + 3);
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  return message;
}

}  // namespace volspline::detail
