#include "vtkMFAReader.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMFAModelData.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <cstring>
#include <exception>
#include <fstream>
#include <memory>

#include "VtkModelImage.h"
#include "core/model/BlockModelFile.h"
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

namespace {

// Whether the regions tile their bounding box (their volumes add up to its volume): then a
// rank's share of blocks is one box, as ordered compositing across ranks assumes.
bool regionsFormABox(const std::vector<mfadvr::vtkglue::CarriedModel>& models) {
  mfadvr::DomainBox all = models.front().region;
  double sum = 0.0;
  for (const auto& m : models) {
    all.min = all.min.cwiseMin(m.region.min);
    all.max = all.max.cwiseMax(m.region.max);
    sum += m.region.extent().prod();
  }
  const double whole = all.extent().prod();
  return std::abs(whole - sum) <= 1e-9 * std::max(whole, 1e-300);
}

}  // namespace

int vtkMFAReader::RequestData(vtkInformation*, vtkInformationVector**,
                              vtkInformationVector* outInfo) {
  vtkDataObject* output = outInfo->GetInformationObject(0)->Get(vtkDataObject::DATA_OBJECT());
  output->Initialize();
  if (!this->FileName || !*this->FileName) {
    vtkErrorMacro("no FileName set");
    return 0;
  }
  // The piece this process reads (ParaView's ranks); one piece without a parallel pipeline.
  vtkInformation* info = outInfo->GetInformationObject(0);
  const int piece = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
                        ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
                        : 0;
  const int pieces = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
                         ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
                         : 1;
  try {
    if (mfadvr::isBlockModelFile(this->FileName)) {
      if (!this->OutputImageData) {
        vtkErrorMacro(<< this->FileName
                      << " is a multi-block model; read it with OutputImageData on (as "
                         "ParaView does) or render it with `mfadvr render`");
        return 0;
      }
      const mfadvr::BlockIndex index = mfadvr::readBlockIndex(this->FileName);
      const size_t count = index.entries.size();
      // Piece p of P reads the blocks [p B / P, (p+1) B / P): contiguous, x fastest.
      const size_t first = count * static_cast<size_t>(piece) / static_cast<size_t>(pieces);
      const size_t last = count * static_cast<size_t>(piece + 1) / static_cast<size_t>(pieces);
      std::vector<mfadvr::vtkglue::CarriedModel> models;
      for (size_t i = first; i < last; ++i) {
        mfadvr::vtkglue::CarriedModel m;
        m.model =
            std::make_shared<const mfadvr::Model>(mfadvr::loadBlock(this->FileName, index, i));
        m.region = index.entries[i].region;
        models.push_back(std::move(m));
      }
      if (models.empty()) {
        return 1;  // more pieces than blocks: this one has nothing to render
      }
      if (pieces > 1 && !regionsFormABox(models)) {
        vtkWarningMacro(<< "piece " << piece << " of " << pieces << " reads blocks " << first
                        << ".." << last - 1 << " of " << this->FileName
                        << ", which do not form a box; parallel compositing orders pieces by "
                           "their bounds and may blend them in the wrong order. Use as many "
                           "ranks as blocks, or a count that splits the block grid into boxes.");
      }
      output->ShallowCopy(mfadvr::vtkglue::imageOfModels(models));
      return 1;
    }
    if (this->OutputImageData && piece != 0) {
      return 1;  // a single model is read and rendered by piece 0 only
    }
    this->SetOutputModel(outInfo,
                         std::make_shared<const mfadvr::Model>(mfadvr::loadModel(this->FileName)));
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
