#include "vtkMFAReader.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMFAModelData.h"
#include "vtkObjectFactory.h"

#include <cstring>
#include <exception>
#include <fstream>
#include <memory>

#include "core/model/Model.h"
#include "core/model/ModelFile.h"

vtkStandardNewMacro(vtkMFAReader);

vtkMFAReader::vtkMFAReader() = default;

vtkMFAReader::~vtkMFAReader() {
  this->SetFileName(nullptr);
}

void vtkMFAReader::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

bool vtkMFAReader::CanReadFile(const char* fileName) {
  if (!fileName) {
    return false;
  }
  std::ifstream in(fileName, std::ios::binary);
  char magic[6] = {};
  in.read(magic, sizeof(magic));
  return in && std::memcmp(magic, "MFADVR", sizeof(magic)) == 0;
}

int vtkMFAReader::RequestData(vtkInformation*, vtkInformationVector**,
                              vtkInformationVector* outInfo) {
  vtkMFAModelData* output = vtkMFAModelData::GetData(outInfo);
  output->Initialize();
  if (!this->FileName || !*this->FileName) {
    vtkErrorMacro("no FileName set");
    return 0;
  }
  try {
    output->SetModel(std::make_shared<const mfadvr::Model>(mfadvr::loadModel(this->FileName)));
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
