#pragma once
// Collects the error messages a VTK object reports (its ErrorEvent), for tests that check them.
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkObject.h>

#include <string>

namespace mfadvr::test {

struct ErrorLog {
  std::string text;
  vtkNew<vtkCallbackCommand> callback;
  explicit ErrorLog(vtkObject* object) {
    callback->SetClientData(this);
    callback->SetCallback([](vtkObject*, unsigned long, void* self, void* message) {
      static_cast<ErrorLog*>(self)->text += static_cast<const char*>(message);
    });
    object->AddObserver(vtkCommand::ErrorEvent, callback);
  }
};

}  // namespace mfadvr::test
