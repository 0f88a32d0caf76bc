#pragma once
// Collects the error (or, asked for, warning) messages a VTK object reports, for tests that
// check them.
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkObject.h>

#include <string>

namespace mfadvr::test {

struct ErrorLog {
  std::string text;
  vtkNew<vtkCallbackCommand> callback;
  explicit ErrorLog(vtkObject* object, unsigned long event = vtkCommand::ErrorEvent) {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void* message) {
      static_cast<ErrorLog*>(self)->text += static_cast<const char*>(message);
    });
    object->AddObserver(event, callback);
  }
};

}  // namespace mfadvr::test
