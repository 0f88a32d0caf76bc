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
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "VtkModelImage.h"
#include "core/model/BlockModelFile.h"
#include "core/model/Model.h"
#include "core/model/ModelFile.h"
#include "core/model/TimeVaryingModel.h"
#include "core/render/RenderMemory.h"

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

// What RequestInformation and RequestData need to know of the file: its blocks' regions (one
// block over the model's box for a single model), the whole box and grid.
struct vtkMFAReader::Layout {
  std::string path;
  std::filesystem::file_time_type time;
  bool multiBlock = false;
  mfadvr::BlockIndex index;                     // multi-block files
  std::shared_ptr<const mfadvr::Model> single;  // single-model files (at the first step)
  // A time-varying single model: every instant.
  std::shared_ptr<const mfadvr::TimeVaryingModel> series;
  std::vector<mfadvr::DomainBox> regions;
  mfadvr::vtkglue::CarrierGrid whole;
};

namespace {

// The blocks piece p of P renders, each with the part of its region this piece renders.
struct Share {
  size_t block = 0;
  mfadvr::DomainBox region;
};

// P <= B: blocks p B / P to (p + 1) B / P - 1, whole. P > B: the pieces with p B / P == b share
// block b, each a slab of its region along the longest axis, cut at grid points (a piece left
// without a slab, when a block is thinner than its pieces, renders nothing).
std::vector<Share> shareOf(int piece, int pieces, const std::vector<mfadvr::DomainBox>& regions,
                           const mfadvr::vtkglue::CarrierGrid& whole) {
  const size_t count = regions.size();
  const size_t p = static_cast<size_t>(piece), n = static_cast<size_t>(pieces);
  std::vector<Share> out;
  if (n <= count) {
    for (size_t i = count * p / n; i < count * (p + 1) / n; ++i) out.push_back({i, regions[i]});
    return out;
  }
  const size_t block = p * count / n;
  size_t first = p, last = p;  // the pieces that share this block
  while (first > 0 && (first - 1) * count / n == block) --first;
  while (last + 1 < n && (last + 1) * count / n == block) ++last;
  const size_t sharing = last - first + 1, at = p - first;
  const mfadvr::vtkglue::CarrierGrid grid = mfadvr::vtkglue::carrierSubGrid(whole, regions[block]);
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (grid.extent[2 * a + 1] - grid.extent[2 * a] >
        grid.extent[2 * axis + 1] - grid.extent[2 * axis])
      axis = a;
  const int lo = grid.extent[2 * axis], cells = grid.extent[2 * axis + 1] - lo;
  const int from = lo + static_cast<int>(cells * at / sharing);
  const int to = lo + static_cast<int>(cells * (at + 1) / sharing);
  if (to <= from) return out;
  Share s{block, regions[block]};
  // The slab's faces: grid points, except the block's own faces (kept exactly).
  if (at > 0) s.region.min[axis] = whole.origin[axis] + from * whole.spacing[axis];
  if (at + 1 < sharing) s.region.max[axis] = whole.origin[axis] + to * whole.spacing[axis];
  out.push_back(s);
  return out;
}

// Refuses, before they are read, models that this process could not hold while it renders them
// (RenderMemory.h): with MPI each rank checks its own share of the blocks.
void requireModelMemory(const std::vector<mfadvr::ModelFileSummary>& models,
                        const std::string& what) {
  mfadvr::requireSceneRenderMemory(models, "reading " + what);
}

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

const vtkMFAReader::Layout& vtkMFAReader::ReadLayout() {
  std::error_code ec;
  const auto time = std::filesystem::last_write_time(this->FileName, ec);
  if (this->Cached && this->Cached->path == this->FileName && !ec && this->Cached->time == time) {
    return *this->Cached;
  }
  auto layout = std::make_shared<Layout>();
  layout->path = this->FileName;
  layout->time = time;
  layout->multiBlock = mfadvr::isBlockModelFile(this->FileName);
  mfadvr::Vec3d step;
  if (layout->multiBlock) {
    layout->index = mfadvr::readBlockIndex(this->FileName);
    for (const auto& e : layout->index.entries) layout->regions.push_back(e.region);
    // Every block stands for samples of one grid: the first one's spacing is the data's.
    step = mfadvr::loadBlock(this->FileName, layout->index, 0).dataSpacing();
    layout->whole = mfadvr::vtkglue::wholeCarrierGrid(layout->index.box, step);
  } else {
    requireModelMemory({mfadvr::summarizeModelFile(this->FileName)}, this->FileName);
    auto series = std::make_shared<const mfadvr::TimeVaryingModel>(
        mfadvr::loadTimeVaryingModel(this->FileName));
    layout->single = std::make_shared<const mfadvr::Model>(series->first());
    if (series->hasTime()) layout->series = std::move(series);
    layout->regions.push_back(layout->single->domain());
    layout->whole =
        mfadvr::vtkglue::wholeCarrierGrid(layout->single->domain(), layout->single->dataSpacing());
  }
  this->Cached = layout;
  return *layout;
}

int vtkMFAReader::RequestInformation(vtkInformation*, vtkInformationVector**,
                                     vtkInformationVector* outInfo) {
  if (!this->FileName || !*this->FileName) {
    return 1;  // RequestData reports a missing name
  }
  try {
    const Layout& layout = this->ReadLayout();
    vtkInformation* info = outInfo->GetInformationObject(0);
    // A time-varying model gives any instant of its range: the steps it was encoded from, and
    // the range, so that an animation may ask for times between them too.
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    if (layout.series) {
      const mfadvr::TimeAxis& axis = layout.series->timeAxis();
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), axis.steps.data(),
                static_cast<int>(axis.steps.size()));
      const double range[2] = {axis.begin, axis.end};
      info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
    }
    if (!this->OutputImageData) {
      return 1;  // a model output has no extent
    }
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), layout.whole.extent, 6);
    info->Set(vtkDataObject::ORIGIN(), layout.whole.origin.data(), 3);
    info->Set(vtkDataObject::SPACING(), layout.whole.spacing.data(), 3);
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

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
    if (!this->OutputImageData && mfadvr::isBlockModelFile(this->FileName)) {
      vtkErrorMacro(<< this->FileName
                    << " is a multi-block model; read it with OutputImageData on (as "
                       "ParaView does) or render it with `mfadvr render`");
      return 0;
    }
    const Layout& layout = this->ReadLayout();
    // The instant asked for (any time in the range; the first step without a request).
    std::shared_ptr<const mfadvr::Model> single = layout.single;
    if (layout.series) {
      const mfadvr::TimeAxis& axis = layout.series->timeAxis();
      double t = layout.series->defaultTime();
      if (info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())) {
        t = info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
      }
      t = std::clamp(t, axis.begin, axis.end);
      if (!this->Instant || this->InstantTime != t || this->InstantOf != layout.series) {
        this->Instant = std::make_shared<const mfadvr::Model>(layout.series->at(t));
        this->InstantTime = t;
        this->InstantOf = layout.series;
      }
      single = this->Instant;
      output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
    }
    if (!this->OutputImageData) {
      this->SetOutputModel(outInfo, single);
      if (layout.series) {
        output = outInfo->GetInformationObject(0)->Get(vtkDataObject::DATA_OBJECT());
        output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), this->InstantTime);
      }
      return 1;
    }
    const std::vector<Share> share =
        shareOf(std::max(piece, 0), std::max(pieces, 1), layout.regions, layout.whole);
    if (share.empty()) {
      return 1;  // a piece without a block (more pieces than the blocks can be cut into)
    }
    if (layout.multiBlock) {
      const std::vector<mfadvr::ModelFileSummary> blocks =
          mfadvr::summarizeBlocks(this->FileName, layout.index);
      std::vector<mfadvr::ModelFileSummary> mine;
      for (const Share& s : share) {
        mine.push_back(blocks[s.block]);
      }
      requireModelMemory(mine, "blocks " + std::to_string(share.front().block) + ".." +
                                   std::to_string(share.back().block) + " of " + this->FileName +
                                   " in piece " + std::to_string(piece) + " of " +
                                   std::to_string(pieces));
    }
    std::vector<mfadvr::vtkglue::CarriedModel> models;
    mfadvr::DomainBox all = share.front().region;
    for (const Share& s : share) {
      mfadvr::vtkglue::CarriedModel m;
      m.model = layout.multiBlock ? std::make_shared<const mfadvr::Model>(
                                        mfadvr::loadBlock(this->FileName, layout.index, s.block))
                                  : single;
      m.region = s.region;
      all.min = all.min.cwiseMin(s.region.min);
      all.max = all.max.cwiseMax(s.region.max);
      models.push_back(std::move(m));
    }
    if (pieces > 1 && !regionsFormABox(models)) {
      vtkWarningMacro(<< "piece " << piece << " of " << pieces << " reads blocks "
                      << share.front().block << ".." << share.back().block << " of "
                      << this->FileName
                      << ", which do not form a box; parallel compositing orders pieces by "
                         "their bounds and may blend them in the wrong order. Use as many "
                         "ranks as blocks, or a count that splits the block grid into boxes.");
    }
    output->ShallowCopy(mfadvr::vtkglue::imageOfModels(
        std::move(models), mfadvr::vtkglue::carrierSubGrid(layout.whole, all)));
    if (layout.series) {
      output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), this->InstantTime);
    }
  } catch (const std::exception& e) {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
