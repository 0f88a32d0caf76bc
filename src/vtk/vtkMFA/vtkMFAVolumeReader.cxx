#include "vtkMFAVolumeReader.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cctype>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/analytic/BuiltinFunction.h"
#include "core/grid/SampleRange.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "io/InputFile.h"
#include "io/RawVolumeReader.h"
#include "io/StreamedVolumeReader.h"
#include "io/VolumeLoader.h"
#include "io/VtkSupport.h"

vtkStandardNewMacro(vtkMFAVolumeReader);

// The file as opened: a box-by-box source; gzip samples, of which the z planes that the
// requests need are inflated into one; or the whole grid read into memory.
struct vtkMFAVolumeReader::Opened {
  std::string path;
  std::filesystem::file_time_type time;
  std::unique_ptr<mfadvr::RawVolumeSource> streamed;
  std::int64_t z0 = 0;  // the first z plane of the file that `streamed` holds
  std::optional<mfadvr::GzipVolume> gzip;
  std::optional<mfadvr::StructuredGrid> whole;
  // The file's whole grid.
  const mfadvr::StructuredGrid& layout() const {
    return gzip ? gzip->layout : streamed ? streamed->layout() : *whole;
  }
  // Whether the output holds the samples as the file stores them (else as float32).
  bool stored() const {
    const bool calibrated = gzip ? gzip->file.calibrated() : streamed && streamed->calibrated();
    return (streamed || gzip) && !calibrated;
  }
};

namespace {

// Whether a legacy VTK file holds structured points (the one data set this reader reads).
bool isLegacyStructuredPoints(const char* fileName) {
  std::ifstream in(fileName, std::ios::binary);
  std::string line;
  for (int n = 0; n < 4 && std::getline(in, line); ++n) {
    std::transform(line.begin(), line.end(), line.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    if (line.rfind("DATASET", 0) == 0) return line.find("STRUCTURED_POINTS") != std::string::npos;
  }
  return false;
}

// The sample box of an update extent (extents count samples from 0 at the grid's first one).
mfadvr::SampleRange rangeOf(const int extent[6]) {
  mfadvr::SampleRange r;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = extent[2 * a];
    r.hi[a] = extent[2 * a + 1];
  }
  return r;
}

}  // namespace

vtkMFAVolumeReader::vtkMFAVolumeReader() {
  this->SetNumberOfInputPorts(0);
}

vtkMFAVolumeReader::~vtkMFAVolumeReader() {
  this->SetFileName(nullptr);
}

void vtkMFAVolumeReader::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}

bool vtkMFAVolumeReader::CanReadFile(const char* fileName) {
  if (!fileName) return false;
  if (mfadvr::isBuiltinSpec(fileName)) return true;
  const std::string ext = mfadvr::lowerExtension(fileName);
  if (ext == ".raw") return mfadvr::parseRawVolumeName(fileName).has_value();
  if (ext == ".vtk") return isLegacyStructuredPoints(fileName);
  return ext == ".nrrd" || ext == ".nhdr" || ext == ".mha" || ext == ".mhd" ||
         mfadvr::isNiftiPath(fileName);
}

vtkMFAVolumeReader::Opened& vtkMFAVolumeReader::Open() {
  if (!this->FileName || !*this->FileName) throw mfadvr::Error("no FileName set");
  std::error_code ec;
  const auto time = std::filesystem::last_write_time(this->FileName, ec);
  if (this->Cached && this->Cached->path == this->FileName && this->Cached->time == time) {
    return *this->Cached;
  }
  this->Cached.reset();  // an inflated copy of the previous file goes now, not after this one
  auto opened = std::make_shared<Opened>();
  opened->path = this->FileName;
  opened->time = time;
  // Gzip samples are inflated when RequestData first needs them: the grid is known without.
  opened->gzip = mfadvr::describeGzipVolume(this->FileName);
  if (!opened->gzip) opened->streamed = mfadvr::openStreamedVolume(this->FileName);
  if (!opened->streamed && !opened->gzip) {
    opened->whole = mfadvr::loadStructuredVolume(this->FileName);
  }
  this->Cached = opened;
  return *opened;
}

void vtkMFAVolumeReader::Inflate(Opened& opened, std::int64_t z0, std::int64_t z1) {
  if (opened.streamed) {
    const std::int64_t heldEnd = opened.z0 + opened.streamed->layout().dims[2] - 1;
    if (opened.z0 <= z0 && z1 <= heldEnd) return;
    z0 = std::min(z0, opened.z0);  // the planes held stay: a later request may want them
    z1 = std::max(z1, heldEnd);
    opened.streamed.reset();  // its temporary file goes before the next one is written
  }
  struct ProgressTextReset {
    vtkAlgorithm* algorithm;
    ~ProgressTextReset() { algorithm->SetProgressText(nullptr); }
  } reset{this};
  this->SetProgressText(("inflating " + opened.path).c_str());
  opened.streamed =
      opened.gzip->openPlanes(z0, z1, [this, &opened](std::int64_t done, std::int64_t total) {
        this->UpdateProgress(static_cast<double>(done) / static_cast<double>(total));
        if (this->GetAbortExecute()) throw mfadvr::Error("reading " + opened.path + " was aborted");
      });
  opened.z0 = z0;
}

int vtkMFAVolumeReader::RequestInformation(vtkInformation*, vtkInformationVector**,
                                           vtkInformationVector* outInfo) {
  try {
    const mfadvr::StructuredGrid& grid = this->Open().layout();
    vtkInformation* info = outInfo->GetInformationObject(0);
    int extent[6];
    double origin[3], spacing[3];
    for (int a = 0; a < 3; ++a) {
      extent[2 * a] = 0;
      extent[2 * a + 1] = static_cast<int>(grid.dims[a] - 1);
      origin[a] = grid.origin[a];
      spacing[a] = grid.spacing[a];
    }
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    info->Set(vtkDataObject::ORIGIN(), origin, 3);
    info->Set(vtkDataObject::SPACING(), spacing, 3);
    info->Set(CAN_PRODUCE_SUB_EXTENT(), 1);
    vtkDataObject::SetPointDataActiveScalarInfo(
        info, this->Cached->stored() ? mfadvr::vtkTypeOfSampleType(grid.sampleType) : VTK_FLOAT, 1);
  } catch (const std::exception& e) {
    this->Cached.reset();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

int vtkMFAVolumeReader::RequestData(vtkInformation*, vtkInformationVector**,
                                    vtkInformationVector* outInfo) {
  vtkInformation* info = outInfo->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(info);
  output->Initialize();
  try {
    Opened& opened = this->Open();
    const mfadvr::StructuredGrid& grid = opened.layout();
    int extent[6];
    info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
    const mfadvr::SampleRange range = rangeOf(extent);
    mfadvr::requireRangeInside(range, grid.dims);
    if (opened.gzip) this->Inflate(opened, range.lo[2], range.hi[2]);
    // The same box in the planes the source holds.
    mfadvr::SampleRange held = range;
    held.lo[2] -= opened.z0;
    held.hi[2] -= opened.z0;
    vtkSmartPointer<vtkDataArray> samples;
    const std::string what = "reading " + opened.path;
    if (opened.stored()) {
      mfadvr::requireMemory(range.sampleCount() * opened.streamed->sampleBytes(), what);
      samples.TakeReference(
          vtkDataArray::CreateDataArray(mfadvr::vtkTypeOfSampleType(grid.sampleType)));
      samples->SetNumberOfTuples(range.sampleCount());
      opened.streamed->readStored(held, samples->GetVoidPointer(0));
    } else {
      mfadvr::requireMemory(range.sampleCount() * std::int64_t{sizeof(float)}, what);
      auto floats = vtkSmartPointer<vtkFloatArray>::New();
      floats->SetNumberOfTuples(range.sampleCount());
      float* out = floats->GetPointer(0);
      if (opened.streamed) {
        opened.streamed->readFloats(held, out);
      } else {
        const mfadvr::Index3& d = grid.dims;
        for (std::int64_t k = range.lo[2]; k <= range.hi[2]; ++k)
          for (std::int64_t j = range.lo[1]; j <= range.hi[1]; ++j) {
            const float* row = grid.values.data() + range.lo[0] + d[0] * (j + d[1] * k);
            out = std::copy(row, row + range.dims()[0], out);
          }
      }
      samples = floats;
    }
    // A raw file names no field: its samples take the name VTK's raw image reader gives them.
    samples->SetName(grid.fieldName.empty() ? "ImageFile" : grid.fieldName.c_str());
    output->SetExtent(extent);
    output->SetOrigin(grid.origin[0], grid.origin[1], grid.origin[2]);
    output->SetSpacing(grid.spacing[0], grid.spacing[1], grid.spacing[2]);
    output->GetPointData()->SetScalars(samples);
  } catch (const std::exception& e) {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
