// mfadvr decode MODEL.mfa -o OUT.nrrd|.nhdr|.raw|.vti [--samples N|NX,NY,NZ] [--type T]
//
// Writes the model's values on a regular grid, slab by slab, so that a coded model can be
// handed to tools that do not read .mfa. NRRD and raw output stream to disk; .vti goes through
// VTK's XML writer, which needs the whole array.
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkTypeFloat32Array.h>
#include <vtkTypeFloat64Array.h>
#include <vtkTypeInt16Array.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt8Array.h>
#include <vtkTypeUInt16Array.h>
#include <vtkTypeUInt32Array.h>
#include <vtkTypeUInt8Array.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "app/Commands.h"
#include "app/FitReportOutput.h"
#include "app/OptionParsing.h"
#include "core/decode/GridDecoder.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/util/AtomicFile.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr::app {
namespace {

// A sample type of the output: its names in NRRD and in `--type`, size, and integer range.
struct SampleType {
  const char* name;
  const char* nrrd;
  int bytes;
  bool integer;
  double lowest, highest;
};

constexpr SampleType kTypes[] = {
    {"float32", "float", 4, false, 0, 0},
    {"float64", "double", 8, false, 0, 0},
    {"uint8", "uint8", 1, true, 0, 255},
    {"int8", "int8", 1, true, -128, 127},
    {"uint16", "uint16", 2, true, 0, 65535},
    {"int16", "int16", 2, true, -32768, 32767},
    {"uint32", "uint32", 4, true, 0, 4294967295.0},
    {"int32", "int32", 4, true, -2147483648.0, 2147483647.0},
};

const SampleType* findType(const std::string& name) {
  for (const SampleType& t : kTypes)
    if (name == t.name) return &t;
  return nullptr;
}

// Values to the type's little-endian bytes: integers rounded and clamped (counted), samples
// outside the domain mask (NaN) as 0 for integer types.
class SampleConverter {
 public:
  explicit SampleConverter(const SampleType& t) : t_(t) {}
  void append(std::span<const double> values, std::string& out) {
    const size_t at = out.size();
    out.resize(at + values.size() * static_cast<size_t>(t_.bytes));
    char* dst = out.data() + at;
    for (double v : values) {
      if (std::isnan(v)) ++outside_;
      switch (t_.bytes * (t_.integer ? 1 : -1)) {
        case -4:
          put(dst, static_cast<float>(v));
          break;
        case -8:
          put(dst, v);
          break;
        default: {
          double r = std::isnan(v) ? 0.0 : std::nearbyint(v);
          if (r < t_.lowest || r > t_.highest) {
            ++clamped_;
            r = std::clamp(r, t_.lowest, t_.highest);
          }
          if (t_.bytes == 1) put(dst, static_cast<std::int8_t>(static_cast<std::int64_t>(r)));
          if (t_.bytes == 2) put(dst, static_cast<std::int16_t>(static_cast<std::int64_t>(r)));
          if (t_.bytes == 4) put(dst, static_cast<std::int32_t>(static_cast<std::int64_t>(r)));
        }
      }
      dst += t_.bytes;
    }
  }
  std::int64_t clamped() const { return clamped_; }
  std::int64_t outside() const { return outside_; }

 private:
  template <class T>
  static void put(char* dst, T v) {
    std::memcpy(dst, &v, sizeof v);
  }
  const SampleType& t_;
  std::int64_t clamped_ = 0, outside_ = 0;
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string nrrdHeader(const DecodeGrid& g, const SampleType& t, const std::string& source,
                       const std::string& dataFile) {
  std::ostringstream h;
  h.precision(17);
  h << "NRRD0004\n# decoded by mfadvr " << MFADVR_VERSION << " from " << source << "\n"
    << "type: " << t.nrrd << "\ndimension: 3\nspace: 3D-right-handed\n"
    << "sizes: " << g.dims[0] << " " << g.dims[1] << " " << g.dims[2] << "\n"
    << "space directions: (" << g.spacing[0] << ",0,0) (0," << g.spacing[1] << ",0) (0,0,"
    << g.spacing[2] << ")\n"
    << "space origin: (" << g.origin[0] << "," << g.origin[1] << "," << g.origin[2] << ")\n"
    << "endian: little\nencoding: raw\n";
  if (!dataFile.empty()) h << "data file: " << dataFile << "\n";
  h << "\n";
  return h.str();
}

template <class ArrayT, class T>
vtkSmartPointer<vtkDataArray> vtkArrayFrom(const std::string& bytes, std::int64_t n) {
  auto a = vtkSmartPointer<ArrayT>::New();
  a->SetNumberOfTuples(n);
  std::memcpy(a->GetPointer(0), bytes.data(), static_cast<size_t>(n) * sizeof(T));
  return a;
}

vtkSmartPointer<vtkDataArray> vtkArrayOf(const SampleType& t, const std::string& bytes,
                                         std::int64_t n) {
  const std::string name = t.name;
  if (name == "float32") return vtkArrayFrom<vtkTypeFloat32Array, float>(bytes, n);
  if (name == "float64") return vtkArrayFrom<vtkTypeFloat64Array, double>(bytes, n);
  if (name == "uint8") return vtkArrayFrom<vtkTypeUInt8Array, std::uint8_t>(bytes, n);
  if (name == "int8") return vtkArrayFrom<vtkTypeInt8Array, std::int8_t>(bytes, n);
  if (name == "uint16") return vtkArrayFrom<vtkTypeUInt16Array, std::uint16_t>(bytes, n);
  if (name == "int16") return vtkArrayFrom<vtkTypeInt16Array, std::int16_t>(bytes, n);
  if (name == "uint32") return vtkArrayFrom<vtkTypeUInt32Array, std::uint32_t>(bytes, n);
  return vtkArrayFrom<vtkTypeInt32Array, std::int32_t>(bytes, n);
}

}  // namespace

Command addDecodeCommand(CLI::App& app) {
  struct Options {
    std::string model, output, samples, type;
    std::optional<double> time;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "decode", "Write a model's values on a regular grid (NRRD, raw or VTK image)");
  sub->add_option("model", o->model, "Model file (.mfa)")->required();
  sub->add_option("-o,--output", o->output,
                  "Output: .nrrd (header and data in one file), .nhdr (header, data in a .raw "
                  "beside it), .raw (data only; the layout is printed) or .vti (VTK XML image)")
      ->required();
  sub->add_option("--samples", o->samples,
                  "Samples N (every axis) or NX,NY,NZ over the model's box (default: the grid "
                  "the model was fitted to, else its data spacing)");
  sub->add_option("--type", o->type,
                  "Sample type: float32, float64, uint8, int8, uint16, int16, uint32, int32 "
                  "(default: the input's type when the model records one of these, else "
                  "float32); integers are rounded and clamped to the type");
  sub->add_option("--time", o->time,
                  "Time-varying models: the instant T to decode (any time in the model's range; "
                  "default: the first step)");
  sub->add_flag("-q,--quiet", o->quiet, "No progress on stderr");

  auto run = [o]() -> int {
    if (isBlockModelFile(o->model))
      throw Error(o->model +
                  ": is a multi-block model; decode reads single models (decoding blocks onto "
                  "one grid is not supported yet)");
    // The file is read whole before it is decoded; slabs of up to 2^24 doubles go to the output.
    const ModelFileSummary summary = summarizeModelFile(o->model);
    requireMemory(loadedModelBytes(summary) + static_cast<std::int64_t>(summary.fileBytes) +
                      (std::int64_t(8) << 24),
                  "decoding " + o->model);
    const TimeVaryingModel series = loadTimeVaryingModel(o->model);
    if (o->time && !series.hasTime())
      throw CLI::ValidationError(
          "--time", "applies to time-varying models; " + o->model + " has no time axis");
    if (o->time && !series.timeAxis().contains(*o->time)) {
      std::ostringstream m;
      m << "--time " << *o->time << " lies outside the time range of " << o->model << " ("
        << series.timeAxis().begin << " .. " << series.timeAxis().end << ")";
      throw Error(m.str());
    }
    const Model model =
        series.hasTime() ? series.at(o->time.value_or(series.defaultTime())) : series.first();
    const std::string ext = lower(std::filesystem::path(o->output).extension().string());
    if (ext != ".nrrd" && ext != ".nhdr" && ext != ".raw" && ext != ".vti")
      throw CLI::ValidationError("--output",
                                 "must end in .nrrd, .nhdr, .raw or .vti, got '" + o->output + "'");
    std::string typeName = o->type;
    if (typeName.empty())
      typeName =
          findType(model.provenance().sampleType) ? model.provenance().sampleType : "float32";
    const SampleType* type = findType(typeName);
    if (!type)
      throw CLI::ValidationError("--type", "unknown type '" + typeName +
                                               "' (float32, float64, uint8, int8, uint16, int16, "
                                               "uint32, int32)");
    DecodeGrid grid = defaultDecodeGrid(model);
    if (!o->samples.empty()) {
      const auto n = parseIntTriple("--samples", o->samples);
      try {
        grid = decodeGridWithSamples(model, {n[0], n[1], n[2]});
      } catch (const Error& e) {
        throw CLI::ValidationError("--samples", e.what());
      }
    }
    const std::int64_t count = grid.dims[0] * grid.dims[1] * grid.dims[2];
    const bool progress = wantProgress(o->quiet);
    SampleConverter convert(*type);
    const std::int64_t slab = std::int64_t(1) << 24;  // samples per slab: ~128 MB of doubles
    auto report = [&](std::int64_t z1) {
      if (progress)
        printProgress("decoding", static_cast<double>(z1) / static_cast<double>(grid.dims[2]));
    };
    if (ext == ".vti") {
      // VTK's writer takes the whole image: the samples and the array made of them.
      requireMemory(2 * count * type->bytes, "decoding " + o->model + " into one .vti image");
      std::string bytes;
      bytes.reserve(static_cast<size_t>(count * type->bytes));
      decodeBySlabs(model, grid, slab, [&](std::int64_t, std::int64_t z1, auto values) {
        convert.append(values, bytes);
        report(z1);
      });
      vtkNew<vtkImageData> image;
      image->SetDimensions(static_cast<int>(grid.dims[0]), static_cast<int>(grid.dims[1]),
                           static_cast<int>(grid.dims[2]));
      image->SetOrigin(grid.origin.data());
      image->SetSpacing(grid.spacing.data());
      auto array = vtkArrayOf(*type, bytes, count);
      const std::string field =
          model.provenance().field.empty() ? "MFA value" : model.provenance().field;
      array->SetName(field.c_str());
      image->GetPointData()->SetScalars(array);
      AtomicFileWriter file(o->output);
      vtkNew<vtkXMLImageDataWriter> writer;
      writer->SetFileName(file.temporaryPath().c_str());
      writer->SetInputData(image);
      writer->SetDataModeToAppended();
      writer->SetCompressorTypeToZLib();
      if (writer->Write() != 1) throw Error("cannot write " + o->output);
      file.commit();
    } else {
      std::filesystem::path dataPath = o->output;
      std::unique_ptr<AtomicFileWriter> header;
      if (ext == ".nhdr") {
        dataPath.replace_extension(".raw");
        header = std::make_unique<AtomicFileWriter>(o->output);
        header->write(nrrdHeader(grid, *type, o->model, dataPath.filename().string()));
      }
      AtomicFileWriter data(dataPath);
      if (ext == ".nrrd") data.write(nrrdHeader(grid, *type, o->model, ""));
      decodeBySlabs(model, grid, slab, [&](std::int64_t, std::int64_t z1, auto values) {
        std::string bytes;
        convert.append(values, bytes);
        data.write(bytes);
        report(z1);
      });
      data.commit();
      if (header) header->commit();
    }
    if (progress) std::cerr << "\n";
    std::printf(
        "wrote %s: %lld x %lld x %lld %s samples (x fastest, little-endian), origin "
        "(%g, %g, %g), spacing (%g, %g, %g)\n",
        o->output.c_str(), static_cast<long long>(grid.dims[0]),
        static_cast<long long>(grid.dims[1]), static_cast<long long>(grid.dims[2]), type->name,
        grid.origin[0], grid.origin[1], grid.origin[2], grid.spacing[0], grid.spacing[1],
        grid.spacing[2]);
    if (convert.clamped() > 0)
      std::cerr << "mfadvr: note: " << groupDigits(convert.clamped())
                << " samples were clamped to the " << type->name << " range\n";
    if (convert.outside() > 0)
      std::cerr << "mfadvr: note: " << groupDigits(convert.outside())
                << " samples lie outside the model's domain mask: written as "
                << (type->integer ? "0" : "NaN") << "\n";
    return 0;
  };
  return {sub, run};
}

}  // namespace mfadvr::app
