#include "io/VtkSupport.h"

#include <cctype>
#include <iostream>
#include <mutex>
#include <regex>
#include <sstream>
#include <type_traits>
#include <vector>

#include <vtkAbstractArray.h>
#include <vtkDataArray.h>
#include <vtkDataReader.h>
#include <vtkFieldData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkType.h>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

// Whether a message (a VTK warning, or text MetaIO writes to std::cerr) says that data could
// not be read: such reads leave zeros where the data should be.
bool reportsUnreadData(const std::string& text) {
  std::string lower = text;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* sign :
       {"error reading", "not read completely", "unexpected end", "premature", "truncated",
        "cannot read", "unable to read", "could not read", "failed to read", "read error"})
    if (lower.find(sign) != std::string::npos) return true;
  return false;
}

// Keeps the text of VTK's error messages so that it ends up in an mfadvr::Error instead of on
// the user's terminal.
class CollectingOutputWindow : public vtkOutputWindow {
 public:
  static CollectingOutputWindow* New();
  vtkTypeMacro(CollectingOutputWindow, vtkOutputWindow);

  void DisplayText(const char* text) override {
    if (!text) return;
    // Most warnings (e.g. NRRD fields VTK ignores) do not stop a read and are dropped, which
    // keeps the terminal quiet. But VTK's readers also report data they could not read as a
    // warning (the legacy reader's "Error reading binary data!" on a truncated file) and then
    // return zeros: those are errors here.
    const MessageTypes type = GetCurrentMessageType();
    if (type == MESSAGE_TYPE_ERROR || reportsUnreadData(text)) addCleaned(errors, text);
  }

  std::vector<std::string> errors;

 protected:
  CollectingOutputWindow() = default;

 private:
  // VTK's text is "ERROR: In SOURCE.cxx, line N\nClass (0xADDR): message\n[object dump]";
  // only the message helps a user.
  static void addCleaned(std::vector<std::string>& into, const std::string& text) {
    std::istringstream lines(text);
    std::string line;
    std::string message;
    while (std::getline(lines, line)) {
      if (line.rfind("ERROR: In ", 0) == 0 || line.rfind("Warning: In ", 0) == 0) continue;
      if (line.rfind("Generic Warning: In ", 0) == 0) continue;
      if (line.empty()) continue;
      message = line;
      break;
    }
    static const std::regex address(R"( \(0x[0-9a-fA-F]+\))");
    message = std::regex_replace(message, address, "");
    // The executive's follow-up only repeats that the reader failed.
    if (message.empty() || message.find("returned failure for request") != std::string::npos)
      return;
    if (!into.empty() && into.back() == message) return;
    into.push_back(message);
  }
};
vtkStandardNewMacro(CollectingOutputWindow);

std::mutex& captureMutex() {
  static std::mutex m;
  return m;
}

}  // namespace

struct VtkMessageCapture::State {
  std::lock_guard<std::mutex> lock{captureMutex()};
  vtkNew<CollectingOutputWindow> window;
  vtkOutputWindow* previousWindow = nullptr;
  vtkLogger::Verbosity previousVerbosity = vtkLogger::VERBOSITY_INFO;
  std::ostringstream cerrText;
  std::streambuf* previousCerr = nullptr;
};

VtkMessageCapture::VtkMessageCapture() : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.previousWindow = vtkOutputWindow::GetInstance();
  if (s.previousWindow) s.previousWindow->Register(nullptr);
  vtkOutputWindow::SetInstance(s.window);
  // vtkLogger prints errors to stderr on its own, besides the output window. It has no getter
  // for the stderr level; the overall cutoff equals it unless a log file asks for more.
  s.previousVerbosity = vtkLogger::GetCurrentVerbosityCutoff();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  s.previousCerr = std::cerr.rdbuf(s.cerrText.rdbuf());
}

VtkMessageCapture::~VtkMessageCapture() {
  State& s = *state_;
  std::cerr.rdbuf(s.previousCerr);
  vtkLogger::SetStderrVerbosity(s.previousVerbosity);
  vtkOutputWindow::SetInstance(s.previousWindow);
  if (s.previousWindow) s.previousWindow->UnRegister(nullptr);
}

bool VtkMessageCapture::hasErrors() const {
  return !state_->window->errors.empty() || reportsUnreadData(state_->cerrText.str());
}

std::string VtkMessageCapture::errorText() const {
  std::string out;
  for (const auto& e : state_->window->errors) out += (out.empty() ? "" : "; ") + e;
  std::istringstream lines(state_->cerrText.str());
  std::string line;
  while (std::getline(lines, line)) {
    if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
  }
  return out;
}

void readAllLegacyArrays(vtkDataReader* reader) {
  reader->ReadAllScalarsOn();
  reader->ReadAllVectorsOn();
  reader->ReadAllColorScalarsOn();
  reader->ReadAllFieldsOn();
}

std::string vtkSampleTypeName(vtkDataArray* array) {
  const std::string bits = std::to_string(array->GetDataTypeSize() * 8);
  switch (array->GetDataType()) {
    case VTK_FLOAT:
    case VTK_DOUBLE:
      return "float" + bits;
    case VTK_CHAR:
      return (std::is_signed_v<char> ? "int" : "uint") + bits;
    case VTK_SIGNED_CHAR:
    case VTK_SHORT:
    case VTK_INT:
    case VTK_LONG:
    case VTK_LONG_LONG:
    case VTK_ID_TYPE:
      return "int" + bits;
    case VTK_UNSIGNED_CHAR:
    case VTK_UNSIGNED_SHORT:
    case VTK_UNSIGNED_INT:
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG:
      return "uint" + bits;
    default:
      return "";
  }
}

int vtkTypeOfSampleType(const std::string& name) {
  if (name == "uint8") return VTK_UNSIGNED_CHAR;
  if (name == "int8") return VTK_SIGNED_CHAR;
  if (name == "uint16") return VTK_UNSIGNED_SHORT;
  if (name == "int16") return VTK_SHORT;
  if (name == "uint32") return VTK_UNSIGNED_INT;
  if (name == "int32") return VTK_INT;
  if (name == "float32") return VTK_FLOAT;
  if (name == "float64") return VTK_DOUBLE;
  throw Error("internal: no VTK type for sample type " + name);
}

std::string describeVtkArrays(vtkFieldData* data) {
  std::string out;
  for (int i = 0; data && i < data->GetNumberOfArrays(); ++i) {
    vtkAbstractArray* a = data->GetAbstractArray(i);
    if (!a) continue;
    std::string entry = a->GetName() ? std::string("'") + a->GetName() + "'" : "(unnamed)";
    if (a->GetNumberOfComponents() != 1)
      entry += " (" + std::to_string(a->GetNumberOfComponents()) + " components)";
    out += (out.empty() ? "" : ", ") + entry;
  }
  return out.empty() ? "none" : out;
}

}  // namespace mfadvr
