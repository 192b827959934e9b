#pragma once
// VTK's readers report problems as ErrorEvents (and print them unless observed). The tetrahedral
// mesh reader (mesh/) and the volume data reader (io/) attach this collector to a reader and turn
// the first error into an InvalidInput that names the file; warnings are observed only so that
// VTK does not print them.
#include <cctype>
#include <mutex>
#include <string>
#include <type_traits>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>
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

// VTK's legacy readers report values they could not read ("Error reading ascii data. Possible
// mismatch of datasize with declaration.") as generic warnings, from functions that belong to no
// object, so no observer sees them: they go to the output window. This one, installed for the
// time of a read, keeps the first warning or error instead of printing it.
class CapturingOutputWindow : public vtkOutputWindow {
 public:
  // vtkStandardNewMacro's body, inline: this header is included by several files.
  static CapturingOutputWindow* New() {
    auto* window = new CapturingOutputWindow;
    window->InitializeObjectBase();
    return window;
  }
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char* text) override { keep(text); }
  void DisplayWarningText(const char* text) override { keep(text); }
  void DisplayGenericWarningText(const char* text) override { keep(text); }
  void DisplayDebugText(const char*) override {}
  std::string first;

 private:
  void keep(const char* text) {
    if (first.empty() && text) first = text;
  }
};

// Installs a CapturingOutputWindow until it goes, then the window that was there. The window is
// VTK's, global to the process: reads that capture are one at a time (a mutex; Python may read
// on several threads). VTK's logger still prints the warning's line on stderr before our error:
// its stderr level cannot be read back to restore it, so it is left alone.
class CapturedOutput {
 public:
  CapturedOutput() : lock_(mutex()), previous_(vtkOutputWindow::GetInstance()) { vtkOutputWindow::SetInstance(window_); }
  ~CapturedOutput() { vtkOutputWindow::SetInstance(previous_); }
  CapturedOutput(const CapturedOutput&) = delete;
  CapturedOutput& operator=(const CapturedOutput&) = delete;
  /// The first message, without VTK's "Generic Warning: In FILE, line N" line.
  std::string first() const {
    const std::string& m = window_->first;
    const auto newline = m.find('\n');
    std::string text = m.rfind("Generic Warning", 0) == 0 && newline != std::string::npos ? m.substr(newline + 1) : m;
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
    return text;
  }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkNew<CapturingOutputWindow> window_;
};

/// A VTK message without its "ERROR: In FILE, line N\nvtkClass (0x...): " prefix.
inline std::string vtk_message_text(std::string message) {
  const auto colon = message.find("): ");
  if (colon != std::string::npos) message = message.substr(colon + 3);
  while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
  return message;
}

}  // namespace volspline::detail
