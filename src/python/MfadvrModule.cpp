// mfadvr._mfadvr: numpy in, numpy out over the core library (docs/python.md). Options are the
// command line's, parsed by its own option classes (app/EncodeCliOptions.h, CodingCliOptions.h,
// RenderOptions.h): a keyword `max_error=0.01` is `--max-error 0.01`, with the same defaults,
// checks and messages, and a render gives the pixels `mfadvr render` writes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/task_arena.h>

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/BlockChoice.h"
#include "app/CodingCliOptions.h"
#include "app/EncodeCliOptions.h"
#include "app/FitReportOutput.h"
#include "app/ModelInfoJson.h"
#include "app/RenderOptions.h"
#include "app/SceneLoader.h"
#include "core/decode/GridDecoder.h"
#include "core/encode/Encoder.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/StructuredEncoder.h"
#include "core/encode/TimeSeriesEncoder.h"
#include "core/image/Image.h"
#include "core/model/BlockLocator.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"
#include "core/model/TimeVaryingModel.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "vtkMFAModelData.h"

namespace py = pybind11;
using namespace mfadvr;

namespace {

// A model, or a multi-block model (`encode --blocks`: blocks, each a model with the region it
// stands for), and, when it was encoded here, the fit report (`encode --json`'s).
struct PyModel {
  std::shared_ptr<const Model> model;  // the model, or a multi-block model's first block's
  std::shared_ptr<const std::vector<ModelBlock>> blocks;  // null for a single model
  Index3 blockGrid{1, 1, 1};                              // blocks per axis
  nlohmann::json report;                                  // null for a loaded model
  // A time-varying model (docs/time-varying.md): every instant; `model` is its first step's.
  std::shared_ptr<const TimeVaryingModel> series;

  PyModel(std::shared_ptr<const Model> m, nlohmann::json r)
      : model(std::move(m)), report(std::move(r)) {}
  PyModel(std::vector<ModelBlock> b, const Index3& grid, nlohmann::json r)
      : blocks(std::make_shared<const std::vector<ModelBlock>>(std::move(b))),
        blockGrid(grid),
        report(std::move(r)) {
    BlockLocator(*blocks, grid);  // checks that the blocks form the grid
    model = std::shared_ptr<const Model>(blocks, &blocks->front().model);  // shares, no copy
  }
};

py::object toPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

// A keyword's value as the command line's text: a sequence's items joined by commas.
std::string optionText(const py::handle value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (!py::isinstance<py::sequence>(value)) return py::str(value).cast<std::string>();
  std::string joined;
  for (const py::handle v : value.cast<py::sequence>()) {
    if (!joined.empty()) joined += ",";
    joined += py::str(v).cast<std::string>();
  }
  return joined;
}

// Keyword arguments as the command line's arguments: name_with_underscores=value becomes
// --name-with-underscores VALUE; True a flag, False and None nothing; a sequence its items
// joined by commas (x, y, z order, as NX,NY,NZ on the command line).
std::vector<std::string> commandLine(const py::kwargs& kwargs) {
  std::vector<std::string> args;
  for (const auto& item : kwargs) {
    std::string name = py::str(item.first);
    for (char& c : name)
      if (c == '_') c = '-';
    const py::handle value = item.second;
    if (value.is_none()) continue;
    if (py::isinstance<py::bool_>(value)) {
      if (value.cast<bool>()) args.push_back("--" + name);
      continue;
    }
    if (py::isinstance<py::str>(value)) {
      args.push_back("--" + name);
      args.push_back(value.cast<std::string>());
      continue;
    }
    const bool sequence = py::isinstance<py::sequence>(value);
    bool strings = sequence && py::len(value) > 0;
    if (sequence)
      for (const py::handle v : value.cast<py::sequence>())
        strings = strings && py::isinstance<py::str>(v);
    if (strings) {
      // A repeatable option (clip_plane=["0,0,0,1,0,0", ...], iso=[...]): once per item.
      for (const py::handle v : value.cast<py::sequence>()) {
        args.push_back("--" + name);
        args.push_back(v.cast<std::string>());
      }
      continue;
    }
    args.push_back("--" + name);
    args.push_back(optionText(value));
  }
  return args;
}

// Parses `args` with the options registered on `app`; a bad option raises ValueError with the
// command line's message.
void parseOptions(CLI::App& app, std::vector<std::string> args) {
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    throw py::value_error(e.what());
  }
}

// Runs f, turning the library's and the options' errors into Python exceptions.
template <class F>
auto translated(F&& f) {
  try {
    return f();
  } catch (const CLI::Error& e) {
    throw py::value_error(e.what());
  } catch (const Error& e) {
    throw std::runtime_error(e.what());
  }
}

// numpy dtype -> the sample type names of the readers (uint8, int16, float32, ...).
std::string sampleTypeOf(const py::dtype& dtype) {
  const char kind = dtype.kind();
  const int bits = static_cast<int>(dtype.itemsize()) * 8;
  if (kind == 'u') return "uint" + std::to_string(bits);
  if (kind == 'i') return "int" + std::to_string(bits);
  if (kind == 'f') return "float" + std::to_string(bits);
  if (kind == 'b') return "uint8";
  throw py::type_error("the array must hold numbers (got dtype " +
                       dtype.attr("name").cast<std::string>() + ")");
}

Vec3d triple(const py::object& value, const char* what, double fill) {
  if (value.is_none()) return Vec3d::Constant(fill);
  if (py::isinstance<py::sequence>(value) && !py::isinstance<py::str>(value)) {
    const auto v = value.cast<std::vector<double>>();
    if (v.size() != 3) throw py::value_error(std::string(what) + ": give three values (x, y, z)");
    return Vec3d(v[0], v[1], v[2]);
  }
  return Vec3d::Constant(value.cast<double>());
}

// A 3-D array indexed [z, y, x] (x fastest in memory for a C-ordered array; any order is read
// by index) as the encoder's grid.
StructuredGrid gridOf(const py::array& input, const py::object& spacing, const py::object& origin) {
  if (input.ndim() != 3)
    throw py::value_error(
        "the array must have 3 dimensions indexed [z, y, x] (4 for a time "
        "series, [t, z, y, x]), got " +
        std::to_string(input.ndim()));
  StructuredGrid g;
  g.dims = {input.shape(2), input.shape(1), input.shape(0)};
  g.spacing = triple(spacing, "spacing", 1.0);
  g.origin = triple(origin, "origin", 0.0);
  for (int a = 0; a < 3; ++a)
    if (!(g.spacing[a] > 0.0) || !std::isfinite(g.spacing[a]) || !std::isfinite(g.origin[a]))
      throw py::value_error("spacing must be positive and origin finite");
  g.sampleType = sampleTypeOf(input.dtype());
  g.source = "numpy array";
  g.inputBytes = static_cast<std::int64_t>(input.nbytes());
  // numpy converts the array (any type, any order) straight into the grid's float32 samples,
  // x fastest: the one copy the encoder needs, none in between.
  g.values.resize(static_cast<size_t>(input.size()));
  py::array_t<float> samples({input.shape(0), input.shape(1), input.shape(2)}, g.values.data(),
                             py::none());  // a view of g.values
  py::module_::import("numpy").attr("copyto")(samples, input, py::arg("casting") = "unsafe");
  for (float x : g.values)
    if (!std::isfinite(x)) throw py::value_error("the array holds NaN or infinite values");
  return g;
}

// `encode`'s fitting and storage options from keywords, as the command line registers them.
// The block keywords (blocks, ghost, memory_limit: `encode --blocks/--ghost/--memory-limit`) are
// taken apart: they are the encode command's own options, not EncodeCliOptions'.
struct EncodeKeywords {
  app::EncodeCliOptions encode;
  app::CodingCliOptions coding;
  app::BlockRequest blocks;

  EncodeKeywords(const char* function, const py::kwargs& kwargs) {
    py::kwargs rest;
    for (const auto& item : kwargs) {
      const std::string name = py::str(item.first);
      const py::handle value = item.second;
      if (name == "blocks") {
        if (!value.is_none()) blocks.blocks = optionText(value);
      } else if (name == "ghost") {
        if (!value.is_none()) blocks.ghost = value.cast<int>();
        if (blocks.ghost < -1 || blocks.ghost > 1024)
          throw py::value_error("--ghost: " + std::to_string(blocks.ghost) +
                                " not in range [0 - 1024]");
      } else if (name == "memory_limit") {
        if (!value.is_none()) blocks.memoryLimit = optionText(value);
      } else {
        rest[item.first] = value;
      }
    }
    CLI::App cli(function);
    encode.addTo(&cli, "Encoding");
    coding.addTo(&cli, "Storage");
    parseOptions(cli, commandLine(rest));
  }
  // Throws CLI::ValidationError (translated() makes it a ValueError).
  EncodeOptions options() const {
    EncodeOptions o = encode.parse();
    o.coding = coding.parse();
    return o;
  }
};

// Runs fit(report) with the GIL released; the model with the fit report of `encode --json`.
template <class Fit>
PyModel fitted(Fit&& fit) {
  FitReport report;
  auto model = std::make_shared<Model>();
  {
    py::gil_scoped_release release;
    *model = fit(report);
  }
  report.peakMemoryBytes = peakResidentBytes();
  return PyModel(model, app::fitReportJson(report, ""));
}

// The blocks of `grid` fitted one at a time (all cores each) with the GIL released, and the
// report of `encode --blocks --json`.
PyModel encodeBlocks(const StructuredGrid& grid, const app::BlockChoice& choice,
                     const EncodeOptions& options) {
  std::vector<FitReport> reports;
  std::vector<ModelBlock> blocks;
  const auto start = std::chrono::steady_clock::now();
  {
    py::gil_scoped_release release;
    blocks = encodeStructuredBlocks(grid, *choice.blocks, choice.ghost, options, &reports);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<DomainBox> regions;
  for (const ModelBlock& b : blocks) regions.push_back(b.region);
  nlohmann::json report =
      app::blockFitReportJson(reports, regions, *choice.blocks, choice.ghost, seconds,
                              peakResidentBytes(), double(grid.inputBytes), "");
  report.erase("output");
  return PyModel(std::move(blocks), *choice.blocks, std::move(report));
}

// The steps of a 4-D array indexed [t, z, y, x], each converted when the encoder asks for it (so
// that only one step is held as float32 besides the caller's array).
class ArraySeries final : public VolumeSeries {
 public:
  ArraySeries(py::array array, std::vector<double> times, py::object spacing, py::object origin)
      : array_(std::move(array)),
        times_(std::move(times)),
        spacing_(std::move(spacing)),
        origin_(std::move(origin)) {}
  int size() const override { return static_cast<int>(times_.size()); }
  double time(int step) const override { return times_[static_cast<size_t>(step)]; }
  std::string stepName(int step) const override {
    return "step " + std::to_string(step) + " of the array";
  }
  std::string source() const override { return "numpy array"; }
  StructuredGrid load(int step) const override {
    py::gil_scoped_acquire gil;  // the encoder runs with the GIL released
    StructuredGrid grid = gridOf(array_[py::int_(step)].cast<py::array>(), spacing_, origin_);
    grid.inputBytes = static_cast<std::int64_t>(array_.nbytes()) / size();
    return grid;
  }

 private:
  py::array array_;
  std::vector<double> times_;
  py::object spacing_, origin_;
};

// `encode` of a time series (docs/time-varying.md): a 4-D array [t, z, y, x] with the keywords
// times=, time_degree=, time_ctrl= (encode --times/--time-degree/--time-ctrl).
PyModel encodeArraySeries(const py::array& array, const py::object& spacing,
                          const py::object& origin, const py::kwargs& kwargs) {
  py::kwargs rest;
  py::object timesGiven = py::none();
  TimeSeriesOptions time;
  time.zfpForIntegerSamples = true;
  for (const auto& item : kwargs) {
    const std::string name = py::str(item.first);
    if (name == "times") {
      timesGiven = py::reinterpret_borrow<py::object>(item.second);
    } else if (name == "time_degree") {
      time.degree = item.second.cast<int>();
      if (time.degree < 1 || time.degree > 7)
        throw py::value_error("--time-degree: " + std::to_string(time.degree) +
                              " not in range [1 - 7]");
    } else if (name == "time_ctrl") {
      time.controlCount = item.second.cast<int>();
      if (time.controlCount < 1) throw py::value_error("--time-ctrl: must be positive");
    } else if (name == "blocks" || name == "ghost" || name == "memory_limit") {
      throw py::value_error("--" + name + ": does not apply to time series yet");
    } else {
      rest[item.first] = item.second;
    }
  }
  const py::ssize_t steps = array.shape(0);
  std::vector<double> times;
  if (timesGiven.is_none()) {
    for (py::ssize_t s = 0; s < steps; ++s) times.push_back(static_cast<double>(s));
  } else {
    times = timesGiven.cast<std::vector<double>>();
    if (times.size() != static_cast<size_t>(steps))
      throw py::value_error("times: " + std::to_string(times.size()) + " times for the " +
                            std::to_string(steps) + " steps of the array");
    for (size_t s = 0; s < times.size(); ++s)
      if (!std::isfinite(times[s]) || (s > 0 && !(times[s] > times[s - 1])))
        throw py::value_error("times must be finite and increase: step " + std::to_string(s) +
                              " has t = " + std::to_string(times[s]));
  }
  if (array.shape(1) < 2 || array.shape(2) < 2 || array.shape(3) < 2)
    throw py::value_error("each step must have at least 2 samples along z, y and x");
  const EncodeKeywords keywords("mfadvr.encode", rest);
  const ArraySeries series(array, std::move(times), spacing, origin);
  return translated([&] {
    EncodeOptions options = keywords.options();
    if (keywords.encode.scatteredOnlyGiven())
      throw CLI::ValidationError("mask_res/no_mask/no_boundary/knot_density/cell_samples",
                                 "apply to meshes and point clouds");
    FitReport report;
    std::vector<std::string> notes;
    auto model = std::make_shared<const TimeVaryingModel>([&] {
      py::gil_scoped_release release;
      return encodeTimeSeries(series, options, time, &report, &notes);
    }());
    for (const std::string& note : notes) PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1);
    report.peakMemoryBytes = peakResidentBytes();
    PyModel out(std::make_shared<Model>(model->first()), app::fitReportJson(report, ""));
    out.series = std::move(model);
    return out;
  });
}

PyModel encodeArray(const py::array& array, const py::object& spacing, const py::object& origin,
                    const py::kwargs& kwargs) {
  if (array.ndim() == 4) return encodeArraySeries(array, spacing, origin, kwargs);
  for (const char* name : {"times", "time_degree", "time_ctrl"})
    if (kwargs.contains(name))
      throw py::value_error(std::string(name) +
                            ": applies to time series (a 4-D array indexed [t, z, y, x])");
  const EncodeKeywords keywords("mfadvr.encode", kwargs);
  const app::EncodeCliOptions& encode = keywords.encode;
  StructuredGrid grid = gridOf(array, spacing, origin);
  return translated([&] {
    EncodeOptions options = keywords.options();
    if (encode.scatteredOnlyGiven())
      throw CLI::ValidationError("mask_res/no_mask/no_boundary/knot_density/cell_samples",
                                 "apply to meshes and point clouds");
    app::requireBlockOptions(keywords.blocks, options, false);
    for (const std::string& note : encode.fitDefaultDegreeToGrid(options, grid.dims))
      PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1);
    app::CodingCliOptions::applyGridDefault(options.coding, grid.sampleType);
    // As `mfadvr encode`: blocks when asked for, or when an in-core fit would need more than the
    // memory limit (a warning says so).
    const app::BlockChoice choice = app::chooseBlocks(grid, keywords.blocks, options);
    if (!choice.note.empty()) PyErr_WarnEx(PyExc_UserWarning, choice.note.c_str(), 1);
    if (choice.blocks) return encodeBlocks(grid, choice, options);
    if (!options.adaptive) {
      Index3 counts = options.controlCounts;
      for (int a = 0; a < 3; ++a)
        if (counts[a] <= 0) counts[a] = grid.dims[a];
      requireMemory(structuredFitPeakBytes(grid.dims, counts),
                    "encoding the array (fewer control points, ctrl=, need less)");
    }
    return fitted([&](FitReport& report) { return encodeStructured(grid, options, &report); });
  });
}

// Scattered points, or a tetrahedral mesh when `tets` is an (M, 4) array of point indices: the
// mesh gets what `mfadvr encode` gives a mesh file (mask, exact boundary, cell samples, knots
// that follow the points).
PyModel encodePoints(const py::array& xyz, const py::array& values, const py::object& tets,
                     const py::kwargs& kwargs) {
  for (const char* name : {"blocks", "ghost", "memory_limit"})
    if (kwargs.contains(name))
      throw py::value_error(std::string("--") + name +
                            ": applies to regular grids (mfadvr.encode of an array)");
  const EncodeKeywords keywords("mfadvr.encode_points", kwargs);
  const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(xyz);
  const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!p || p.ndim() != 2 || p.shape(1) != 3)
    throw py::value_error("points must be an (N, 3) array of x, y, z");
  if (!v || v.ndim() != 1 || v.shape(0) != p.shape(0))
    throw py::value_error("values must be an (N,) array, one per point");
  ScatteredData data;
  data.source = tets.is_none() ? "numpy points" : "numpy mesh";
  data.kind = tets.is_none() ? "point cloud" : "tetrahedral mesh";
  data.fieldAssociation = "point data";
  if (!tets.is_none()) {
    const py::array given = py::array::ensure(tets);
    if (!given || given.ndim() != 2 || given.shape(1) != 4 || given.shape(0) == 0 ||
        !(given.dtype().kind() == 'i' || given.dtype().kind() == 'u'))
      throw py::value_error("tets must be an (M, 4) integer array of point indices, M > 0");
    const auto t =
        py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(given);
    data.tets.resize(static_cast<size_t>(t.shape(0)));
    for (py::ssize_t c = 0; c < t.shape(0); ++c)
      for (int k = 0; k < 4; ++k) {
        const std::int64_t index = t.at(c, k);
        if (index < 0 || index >= p.shape(0))
          throw py::value_error("tets: tetrahedron " + std::to_string(c) + " has point index " +
                                std::to_string(index) + ", outside 0.." +
                                std::to_string(p.shape(0) - 1));
        data.tets[static_cast<size_t>(c)][static_cast<size_t>(k)] = index;
      }
    data.inputCells = static_cast<std::int64_t>(data.tets.size());
  }
  data.fieldName = "value";
  data.sampleType = sampleTypeOf(values.dtype());
  const std::int64_t n = p.shape(0);
  data.points.resize(static_cast<size_t>(n));
  data.values.assign(v.data(), v.data() + n);
  for (std::int64_t i = 0; i < n; ++i) {
    data.points[i] = Vec3d(p.at(i, 0), p.at(i, 1), p.at(i, 2));
    if (!data.points[i].allFinite() || !std::isfinite(data.values[i]))
      throw py::value_error("point " + std::to_string(i) +
                            " has a NaN or infinite coordinate or value");
  }
  data.inputBytes = static_cast<std::int64_t>(values.nbytes());
  return translated([&] {
    const EncodeOptions options = keywords.options();
    return fitted([&](FitReport& report) { return encodeScattered(data, options, &report); });
  });
}

// A multi-block model's values (and derivatives, where the spans are not empty) at `at`: each
// point by the block whose region holds it (core/model/BlockLocator.h), the points of a block
// gathered and evaluated together over all cores.
void evaluateBlocks(const PyModel& m, std::span<const Vec3d> at, std::span<float> values,
                    std::span<Vec3f> gradients, std::span<Sym3f> hessians) {
  const std::vector<ModelBlock>& blocks = *m.blocks;
  const BlockLocator locator(blocks, m.blockGrid);
  std::vector<std::vector<size_t>> members(blocks.size());
  for (size_t i = 0; i < at.size(); ++i) members[locator.blockOf(at[i])].push_back(i);
  std::vector<Vec3d> points;
  std::vector<float> v;
  std::vector<Vec3f> g;
  std::vector<Sym3f> h;
  for (size_t b = 0; b < blocks.size(); ++b) {
    const std::vector<size_t>& mine = members[b];
    if (mine.empty()) continue;
    points.resize(mine.size());
    for (size_t k = 0; k < mine.size(); ++k) points[k] = at[mine[k]];
    v.resize(mine.size());
    g.resize(gradients.empty() ? 0 : mine.size());
    h.resize(hessians.empty() ? 0 : mine.size());
    blocks[b].model.evaluate(points, v, g, h);
    for (size_t k = 0; k < mine.size(); ++k) {
      values[mine[k]] = v[k];
      if (!g.empty()) gradients[mine[k]] = g[k];
      if (!h.empty()) hessians[mine[k]] = h[k];
    }
  }
}

// (N,) values, (N, 4) value and gradient, (N, 10) with the Hessian (dxx, dxy, dxz, dyy, dyz,
// dzz): the columns of `mfadvr query`.
// A time-varying model at points with their times: (N,) values, or with derivatives=1 (N, 5)
// value, dx, dy, dz, dt (the columns of `mfadvr query` for x y z t). points: (N, 4) x, y, z, t,
// or (N, 3) with `times` one number or (N,).
py::array_t<float> queryInTime(const PyModel& m, const py::object& points, const py::object& times,
                               int derivatives, int threads) {
  if (derivatives == 2)
    throw py::value_error("second derivatives of a time-varying model: query model.at(t)");
  const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  const bool withTimes = !times.is_none();
  const py::ssize_t columns = withTimes ? 3 : 4;
  if (!p || !((p.ndim() == 2 && p.shape(1) == columns) || (p.ndim() == 1 && p.shape(0) == columns)))
    throw py::value_error(withTimes ? "points must be an (N, 3) array of x, y, z with times="
                                    : "points of a time-varying model must be an (N, 4) array of "
                                      "x, y, z, t (or (N, 3) with times=)");
  const size_t n = p.ndim() == 2 ? static_cast<size_t>(p.shape(0)) : 1;
  std::vector<Vec3d> at(n);
  std::vector<double> t(n);
  const double* v = p.data();
  for (size_t i = 0; i < n; ++i) {
    at[i] = Vec3d(v[columns * i], v[columns * i + 1], v[columns * i + 2]);
    if (!withTimes) t[i] = v[columns * i + 3];
  }
  if (withTimes) {
    const auto ts = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(times);
    if (!ts || !(ts.size() == 1 || ts.size() == static_cast<py::ssize_t>(n)))
      throw py::value_error("times must be one number or one per point");
    for (size_t i = 0; i < n; ++i) t[i] = ts.data()[ts.size() == 1 ? 0 : i];
  }
  for (size_t i = 0; i < n; ++i)
    if (!at[i].allFinite() || !std::isfinite(t[i]))
      throw py::value_error("points and times must be finite");
  std::vector<float> values(n), rates(derivatives >= 1 ? n : 0);
  std::vector<Vec3f> gradients(derivatives >= 1 ? n : 0);
  {
    py::gil_scoped_release release;
    const auto run = [&] { m.series->evaluate(at, t, values, gradients, rates); };
    if (threads == 0) {
      run();
    } else {
      tbb::task_arena arena(threads);
      arena.execute(run);
    }
  }
  if (derivatives == 0) {
    py::array_t<float> out(static_cast<py::ssize_t>(n));
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
  }
  py::array_t<float> out({static_cast<py::ssize_t>(n), py::ssize_t(5)});
  float* o = out.mutable_data();
  for (size_t i = 0; i < n; ++i, o += 5) {
    o[0] = values[i];
    for (int a = 0; a < 3; ++a) o[1 + a] = gradients[i][a];
    o[4] = rates[i];
  }
  return out;
}

py::array_t<float> query(const PyModel& m, const py::object& points, int derivatives, int threads,
                         const py::object& times) {
  if (derivatives < 0 || derivatives > 2) throw py::value_error("derivatives must be 0, 1 or 2");
  if (threads < 0) throw py::value_error("threads must be 0 (all cores) or more");
  if (m.series) return queryInTime(m, points, times, derivatives, threads);
  if (!times.is_none())
    throw py::value_error("times= applies to time-varying models; this one has no time axis");
  const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(points);
  if (!p || !((p.ndim() == 2 && p.shape(1) == 3) || (p.ndim() == 1 && p.shape(0) == 3)))
    throw py::value_error("points must be an (N, 3) array of x, y, z (physical coordinates)");
  const size_t n = p.ndim() == 2 ? static_cast<size_t>(p.shape(0)) : 1;
  const double* xyz = p.data();
  for (size_t i = 0; i < 3 * n; ++i)
    if (!std::isfinite(xyz[i])) throw py::value_error("points must be finite");
  // Vec3d is three packed doubles: the array's rows are read in place.
  static_assert(sizeof(Vec3d) == 3 * sizeof(double));
  const std::span<const Vec3d> at(reinterpret_cast<const Vec3d*>(xyz), n);
  const auto evaluate = [&](std::span<float> values, std::span<Vec3f> gradients,
                            std::span<Sym3f> hessians) {
    py::gil_scoped_release release;
    const auto run = [&] {
      if (m.blocks)
        evaluateBlocks(m, at, values, gradients, hessians);
      else
        m.model->evaluate(at, values, gradients, hessians);
    };
    if (threads == 0) {
      run();
    } else {
      tbb::task_arena arena(threads);
      arena.execute(run);
    }
  };
  if (derivatives == 0) {  // straight into the returned array
    py::array_t<float> out(static_cast<py::ssize_t>(n));
    evaluate({out.mutable_data(), n}, {}, {});
    return out;
  }
  std::vector<float> values(n);
  std::vector<Vec3f> gradients(n);
  std::vector<Sym3f> hessians(derivatives >= 2 ? n : 0);
  evaluate(values, gradients, hessians);
  const int columns = derivatives == 1 ? 4 : 10;
  py::array_t<float> out({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(columns)});
  float* o = out.mutable_data();
  for (size_t i = 0; i < n; ++i, o += columns) {
    o[0] = values[i];
    for (int a = 0; a < 3; ++a) o[1 + a] = gradients[i][a];
    if (derivatives == 2)
      for (int a = 0; a < 6; ++a) o[4 + a] = hessians[i][a];
  }
  return out;
}

// A multi-block model's grid: the input's spacing over the union of the regions, or `dims`
// samples over it.
DecodeGrid blocksDecodeGrid(const PyModel& m, const std::optional<Index3>& dims) {
  const DomainBox box = regionsBox(*m.blocks);
  DecodeGrid grid;
  grid.origin = box.min;
  const Vec3d spacing = defaultDecodeGrid(*m.model).spacing;
  for (int a = 0; a < 3; ++a) {
    const double extent = box.max[a] - box.min[a];
    if (dims) {
      if ((*dims)[a] < 2) throw Error("decoding needs at least 2 samples per axis");
      grid.dims[a] = (*dims)[a];
    } else {
      grid.dims[a] = std::llround(extent / spacing[a]) + 1;
    }
    grid.spacing[a] = extent / double(grid.dims[a] - 1);
  }
  return grid;
}

// Decodes a multi-block model on `grid` into `out` ([z, y, x]): each block the samples in its
// region (along each axis, those BlockLocator gives it).
void decodeBlocks(const PyModel& m, const DecodeGrid& grid, double* out) {
  const BlockLocator locator(*m.blocks, m.blockGrid);
  // Per axis and block along it: the first sample and one past the last.
  std::array<std::vector<std::int64_t>, 3> first;
  for (int a = 0; a < 3; ++a) {
    first[a].assign(static_cast<size_t>(m.blockGrid[a] + 1), grid.dims[a]);
    for (std::int64_t k = grid.dims[a] - 1; k >= 0; --k)
      first[a][locator.axisBlock(a, grid.origin[a] + double(k) * grid.spacing[a])] = k;
    for (std::int64_t b = m.blockGrid[a] - 1; b >= 0; --b)  // blocks with no sample: empty
      first[a][b] = std::min(first[a][b], first[a][b + 1]);
  }
  for (std::int64_t bz = 0; bz < m.blockGrid[2]; ++bz)
    for (std::int64_t by = 0; by < m.blockGrid[1]; ++by)
      for (std::int64_t bx = 0; bx < m.blockGrid[0]; ++bx) {
        const Index3 b{bx, by, bz};
        Index3 k0, count;
        for (int a = 0; a < 3; ++a) {
          k0[a] = first[a][b[a]];
          count[a] = first[a][b[a] + 1] - k0[a];
        }
        if (count[0] <= 0 || count[1] <= 0 || count[2] <= 0) continue;
        const Model& model =
            (*m.blocks)[static_cast<size_t>(bx + m.blockGrid[0] * (by + m.blockGrid[1] * bz))]
                .model;
        // The block's samples a z plane at a time, by point evaluation (a block's samples lie
        // in its region, not on a grid spanning its model's box, which decodeBySlabs takes).
        std::vector<Vec3d> points(static_cast<size_t>(count[0] * count[1]));
        std::vector<float> values(points.size());
        for (std::int64_t z = k0[2]; z < k0[2] + count[2]; ++z) {
          for (std::int64_t y = 0; y < count[1]; ++y)
            for (std::int64_t x = 0; x < count[0]; ++x)
              points[static_cast<size_t>(y * count[0] + x)] =
                  grid.origin +
                  Vec3d(double(k0[0] + x), double(k0[1] + y), double(z)).cwiseProduct(grid.spacing);
          model.evaluate(points, values, {}, {});
          for (std::int64_t y = 0; y < count[1]; ++y)
            std::copy_n(values.begin() + y * count[0], count[0],
                        out + (z * grid.dims[1] + k0[1] + y) * grid.dims[0] + k0[0]);
        }
      }
}

// The model on its grid (or `shape` samples over its box), float64 [z, y, x]; NaN outside a
// domain mask. The Python side converts to the input's type.
py::array_t<double> decodeValues(const PyModel& m, const py::object& shape) {
  return translated([&] {
    std::optional<Index3> dims;
    if (!shape.is_none()) {
      const auto s = shape.cast<std::vector<std::int64_t>>();
      if (s.size() != 3) throw py::value_error("shape must be (nz, ny, nx)");
      dims = Index3{s[2], s[1], s[0]};
    }
    const DecodeGrid grid = m.blocks ? blocksDecodeGrid(m, dims)
                            : dims   ? decodeGridWithSamples(*m.model, *dims)
                                     : defaultDecodeGrid(*m.model);
    const std::int64_t count = grid.dims[0] * grid.dims[1] * grid.dims[2];
    requireMemory(8 * count, "decoding the model");
    py::array_t<double> out({grid.dims[2], grid.dims[1], grid.dims[0]});
    double* dst = out.mutable_data();
    const std::int64_t plane = grid.dims[0] * grid.dims[1];
    if (m.blocks) {
      py::gil_scoped_release release;
      decodeBlocks(m, grid, dst);
      return out;
    }
    {
      py::gil_scoped_release release;
      decodeBySlabs(*m.model, grid, std::int64_t(1) << 24,
                    [&](std::int64_t z0, std::int64_t, std::span<const double> values) {
                      std::copy(values.begin(), values.end(), dst + z0 * plane);
                    });
    }
    return out;
  });
}

// `mfadvr render`'s pixels: scene options as its keywords, the model (or an array, encoded
// with the encoding keywords unless a grid method renders it).
py::array render(const py::object& input, const py::object& size, const py::object& spacing,
                 const py::object& origin, const std::string& method, bool alpha, bool asFloat,
                 const py::kwargs& kwargs) {
  app::RenderOptions options;
  app::EncodeCliOptions encode;
  CLI::App cli("mfadvr.render");
  options.addTo(&cli);
  encode.addTo(&cli, "Encoding");
  std::vector<std::string> args = commandLine(kwargs);
  if (!size.is_none()) {
    const auto wh = size.cast<std::vector<int>>();
    if (wh.size() != 2) throw py::value_error("size must be (width, height)");
    args.push_back("--size");
    args.push_back(std::to_string(wh[0]) + "x" + std::to_string(wh[1]));
  }
  parseOptions(cli, args);
  MethodSpec spec;
  translated([&] {
    spec.method = parseReconstructionMethod(method);
    return 0;
  });
  if (spec.method == ReconstructionMethod::Truth)
    throw py::value_error("method 'truth' needs a built-in function; render an array or a model");
  if (spec.method == ReconstructionMethod::Mesh)
    throw py::value_error(
        "method 'mesh' renders a mesh file's own field; render() takes arrays and models (use "
        "`mfadvr render MESH --method mesh`)");
  app::LoadedScene scene;
  if (py::isinstance<PyModel>(input)) {
    if (spec.method != ReconstructionMethod::Mfa)
      throw py::value_error("a model renders with method 'mfa'; grid methods need the array");
    const PyModel& m = input.cast<const PyModel&>();
    scene =
        m.blocks ? app::sceneOfBlocks(*m.blocks, "model") : app::sceneOfModel(*m.model, "model");
  } else {
    StructuredGrid grid = gridOf(input.cast<py::array>(), spacing, origin);
    app::SceneNeeds needs;
    needs.model = spec.method == ReconstructionMethod::Mfa;
    needs.grid = isGridMethod(spec.method);
    scene = translated([&] {
      EncodeOptions e = encode.parse();
      encode.fitDefaultDegreeToGrid(e, grid.dims);
      py::gil_scoped_release release;
      return app::sceneOfGrid(std::move(grid), needs, e);
    });
  }
  const Image image = translated([&] {
    const RenderSettings settings = options.settingsFor(scene);
    py::gil_scoped_release release;
    return renderMethod(scene.view(), spec, settings);
  });
  const py::ssize_t h = image.height, w = image.width;
  if (asFloat) {
    py::array_t<float> out({h, w, py::ssize_t(4)});
    std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
    return out;
  }
  const Image8 pixels = toImage8(image, alpha);
  py::array_t<std::uint8_t> out({h, w, py::ssize_t(pixels.channels)});
  std::copy(pixels.data.begin(), pixels.data.end(), out.mutable_data());
  return out;
}

// The VTK object behind a VTK Python object: its `__this__` reads "_<hex address>_p_<class>".
vtkMFAModelData* vtkModelData(const py::object& object) {
  if (!py::hasattr(object, "__this__"))
    throw py::type_error("expected a vtkMFAModelData (a VTK object), got " +
                         py::str(py::type::of(object)).cast<std::string>());
  const std::string text = object.attr("__this__").cast<std::string>();
  const size_t end = text.find("_p_");
  if (text.size() < 2 || text[0] != '_' || end == std::string::npos)
    throw py::type_error("not a VTK object: " + text);
  const auto address =
      static_cast<std::uintptr_t>(std::stoull(text.substr(1, end - 1), nullptr, 16));
  vtkMFAModelData* data = vtkMFAModelData::SafeDownCast(reinterpret_cast<vtkObjectBase*>(address));
  if (!data) throw py::type_error("expected a vtkMFAModelData, got a " + text.substr(end + 3));
  return data;
}

}  // namespace

PYBIND11_MODULE(_mfadvr, m) {
  m.doc() = "mfadvr's core library for numpy arrays (docs/python.md)";
  py::class_<PyModel>(m, "Model", "An MFA model: encoded here, loaded from a .mfa file or saved")
      .def_property_readonly(
          "report",
          [](const PyModel& self) -> py::object {
            return self.report.is_null() ? py::none() : toPython(self.report);
          },
          "The fit report of encode (the CLI's `encode --json`), None for a loaded model")
      .def_property_readonly(
          "info",
          [](const PyModel& self) {
            if (self.series) {
              nlohmann::json j = app::modelInfoJson(*self.model, "", 0);
              j["time"] = app::timeAxisJson(*self.series);
              return toPython(j);
            }
            if (!self.blocks) return toPython(app::modelInfoJson(*self.model, "", 0));
            nlohmann::json entries = nlohmann::json::array();
            for (const ModelBlock& b : *self.blocks)
              entries.push_back(app::blockEntryJson(b.model, b.region));
            return toPython(app::blockModelsInfoJson(self.blockGrid, regionsBox(*self.blocks),
                                                     self.model->valueMin(), self.model->valueMax(),
                                                     entries));
          },
          "The model's description (the CLI's `info --json`; for a multi-block model its "
          "blocks, with format 'mfadvr-blocks')")
      .def_property_readonly(
          "blocks",
          [](const PyModel& self) -> py::object {
            if (!self.blocks) return py::none();
            return py::make_tuple(self.blockGrid[0], self.blockGrid[1], self.blockGrid[2]);
          },
          "Blocks per axis (x, y, z) of a multi-block model (encode's blocks=), None for one model")
      .def_property_readonly(
          "sample_type", [](const PyModel& self) { return self.model->provenance().sampleType; },
          "The input's sample type (uint8, int16, float32, ...), the default dtype of decode")
      .def(
          "save",
          [](const PyModel& self, const std::string& path) {
            translated([&] {
              if (self.blocks)
                saveBlockModels(*self.blocks, self.blockGrid, path);
              else if (self.series)
                saveModel(*self.series, path);
              else
                saveModel(*self.model, path);
              return 0;
            });
          },
          py::arg("path"),
          "Writes the model to a .mfa file (atomically; a multi-block model as a multi-block "
          "file)")
      .def("query", &query, py::arg("points"), py::arg("derivatives") = 0, py::arg("threads") = 0,
           py::arg("times") = py::none(),
           "Values (N,), with derivatives=1 (N, 4) value, dx, dy, dz; with 2 (N, 10) adding "
           "dxx, dxy, dxz, dyy, dyz, dzz; points an (N, 3) array of physical x, y, z; threads: "
           "0 for all cores. A time-varying model takes (N, 4) points x, y, z, t (or (N, 3) "
           "with times= one number or (N,)), and derivatives=1 gives (N, 5) with dt")
      .def(
          "__call__",
          [](const PyModel& self, const py::object& points) {
            return query(self, points, 0, 0, py::none());
          },
          py::arg("points"), "The values at (N, 3) points ((N, 4) with t for a time-varying model)")
      .def_property_readonly(
          "times",
          [](const PyModel& self) -> py::object {
            if (!self.series) return py::none();
            return py::cast(self.series->timeAxis().steps);
          },
          "A time-varying model's steps (the input's times), None for a 3-D model")
      .def(
          "at",
          [](const PyModel& self, double t) {
            if (!self.series)
              throw py::value_error(
                  "at() applies to time-varying models; this one has no time axis");
            const TimeAxis& axis = self.series->timeAxis();
            if (!axis.contains(t))
              throw py::value_error("t = " + std::to_string(t) + " lies outside the time range " +
                                    std::to_string(axis.begin) + " .. " + std::to_string(axis.end));
            std::shared_ptr<const Model> instant;
            {
              py::gil_scoped_release release;
              instant = std::make_shared<const Model>(self.series->at(t));
            }
            return PyModel(instant, nullptr);
          },
          py::arg("t"),
          "The 3-D model at time t (any time in the range): query, decode, render or save it as "
          "any model")
      .def("_decode_values", &decodeValues, py::arg("shape") = py::none())
      .def(
          "_into_vtk",
          [](const PyModel& self, const py::object& data) {
            if (self.blocks)
              throw py::value_error(
                  "a multi-block model is not one vtkMFAModelData: save it and read it with "
                  "vtkMFAReader (OutputImageData), which spreads its blocks over MPI ranks");
            vtkModelData(data)->SetModel(self.model);
          },
          py::arg("data"))
      .def_static(
          "_from_vtk",
          [](const py::object& data) {
            const std::shared_ptr<const Model>& model = vtkModelData(data)->GetModel();
            if (!model) throw py::value_error("the vtkMFAModelData holds no model");
            return PyModel(model, nullptr);
          },
          py::arg("data"));

  m.def("_encode", &encodeArray, py::arg("array"), py::arg("spacing") = py::none(),
        py::arg("origin") = py::none());
  m.def("_encode_points", &encodePoints, py::arg("points"), py::arg("values"),
        py::arg("tets") = py::none());
  m.def(
      "load",
      [](const std::string& path) {
        return translated([&] {
          if (isBlockModelFile(path))
            return PyModel(loadBlockModels(path), readBlockIndex(path).blocks, nullptr);
          auto series = std::make_shared<const TimeVaryingModel>(loadTimeVaryingModel(path));
          PyModel out(std::make_shared<Model>(series->first()), nullptr);
          if (series->hasTime()) out.series = std::move(series);
          return out;
        });
      },
      py::arg("path"), "Reads a .mfa model file (one model or multi-block)");
  m.def("_render", &render, py::arg("input"), py::arg("size") = py::none(),
        py::arg("spacing") = py::none(), py::arg("origin") = py::none(), py::arg("method") = "mfa",
        py::arg("alpha") = false, py::arg("float") = false);
}
