// mfadvr._mfadvr: numpy in, numpy out over the core library (docs/python.md). Options are the
// command line's, parsed by its own option classes (app/EncodeCliOptions.h, CodingCliOptions.h,
// RenderOptions.h): a keyword `max_error=0.01` is `--max-error 0.01`, with the same defaults,
// checks and messages, and a render gives the pixels `mfadvr render` writes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "app/CodingCliOptions.h"
#include "app/EncodeCliOptions.h"
#include "app/FitReportOutput.h"
#include "app/ModelInfoJson.h"
#include "app/RenderOptions.h"
#include "app/SceneLoader.h"
#include "core/decode/GridDecoder.h"
#include "core/encode/Encoder.h"
#include "core/encode/StructuredEncoder.h"
#include "core/image/Image.h"
#include "core/model/ModelFile.h"
#include "core/render/ReconstructionMethod.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "vtkMFAModelData.h"

namespace py = pybind11;
using namespace mfadvr;

namespace {

// A model and, when it was encoded here, the fit report (`encode --json`'s).
struct PyModel {
  std::shared_ptr<const Model> model;
  nlohmann::json report;  // null for a loaded model
};

py::object toPython(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
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
      for (const py::handle v : value.cast<py::sequence>()) strings = strings && py::isinstance<py::str>(v);
    if (strings) {
      // A repeatable option (clip_plane=["0,0,0,1,0,0", ...], iso=[...]): once per item.
      for (const py::handle v : value.cast<py::sequence>()) {
        args.push_back("--" + name);
        args.push_back(v.cast<std::string>());
      }
      continue;
    }
    args.push_back("--" + name);
    if (sequence) {
      std::string joined;
      for (const py::handle v : value.cast<py::sequence>()) {
        if (!joined.empty()) joined += ",";
        joined += py::str(v).cast<std::string>();
      }
      args.push_back(joined);
    } else {
      args.push_back(py::str(value).cast<std::string>());
    }
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
    throw py::value_error("the array must have 3 dimensions indexed [z, y, x], got " +
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
struct EncodeKeywords {
  app::EncodeCliOptions encode;
  app::CodingCliOptions coding;

  EncodeKeywords(const char* function, const py::kwargs& kwargs) {
    CLI::App cli(function);
    encode.addTo(&cli, "Encoding");
    coding.addTo(&cli, "Storage");
    parseOptions(cli, commandLine(kwargs));
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
  return PyModel{model, app::fitReportJson(report, "")};
}

PyModel encodeArray(const py::array& array, const py::object& spacing, const py::object& origin,
                    const py::kwargs& kwargs) {
  for (const char* name : {"blocks", "ghost", "memory_limit"})
    if (kwargs.contains(name))
      throw py::value_error(std::string(name) +
                            ": multi-block models are the command line's (mfadvr encode --blocks "
                            "on a file); the Python module encodes an array whole");
  const EncodeKeywords keywords("mfadvr.encode", kwargs);
  const app::EncodeCliOptions& encode = keywords.encode;
  StructuredGrid grid = gridOf(array, spacing, origin);
  return translated([&] {
    EncodeOptions options = keywords.options();
    if (!encode.maskRes.empty() || encode.noMask)
      throw CLI::ValidationError("mask_res/no_mask", "apply to meshes and point clouds");
    for (const std::string& note : encode.fitDefaultDegreeToGrid(options, grid.dims))
      PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1);
    app::CodingCliOptions::applyGridDefault(options.coding, grid.sampleType);
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

PyModel encodePoints(const py::array& xyz, const py::array& values, const py::kwargs& kwargs) {
  const EncodeKeywords keywords("mfadvr.encode_points", kwargs);
  const auto p = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(xyz);
  const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  if (!p || p.ndim() != 2 || p.shape(1) != 3)
    throw py::value_error("points must be an (N, 3) array of x, y, z");
  if (!v || v.ndim() != 1 || v.shape(0) != p.shape(0))
    throw py::value_error("values must be an (N,) array, one per point");
  ScatteredData data;
  data.source = "numpy points";
  data.kind = "point cloud";
  data.fieldName = "value";
  data.sampleType = sampleTypeOf(values.dtype());
  const std::int64_t n = p.shape(0);
  data.points.resize(static_cast<size_t>(n));
  data.values.assign(v.data(), v.data() + n);
  for (std::int64_t i = 0; i < n; ++i) {
    data.points[i] = Vec3d(p.at(i, 0), p.at(i, 1), p.at(i, 2));
    if (!data.points[i].allFinite() || !std::isfinite(data.values[i]))
      throw py::value_error("point " + std::to_string(i) + " has a NaN or infinite coordinate or value");
  }
  data.inputBytes = static_cast<std::int64_t>(values.nbytes());
  return translated([&] {
    const EncodeOptions options = keywords.options();
    if (options.autoSmoothing)
      throw CLI::ValidationError("smooth", "'auto' is for regular grids; give points a weight");
    return fitted([&](FitReport& report) { return encodeScattered(data, options, &report); });
  });
}

// (N,) values, (N, 4) value and gradient, (N, 10) with the Hessian (dxx, dxy, dxz, dyy, dyz,
// dzz): the columns of `mfadvr query`.
py::array_t<float> query(const PyModel& m, const py::object& points, int derivatives,
                         int threads) {
  if (derivatives < 0 || derivatives > 2) throw py::value_error("derivatives must be 0, 1 or 2");
  if (threads < 0) throw py::value_error("threads must be 0 (all cores) or more");
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
    if (threads == 0) {
      m.model->evaluate(at, values, gradients, hessians);
    } else {
      tbb::task_arena arena(threads);
      arena.execute([&] { m.model->evaluate(at, values, gradients, hessians); });
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

// The model on its grid (or `shape` samples over its box), float64 [z, y, x]; NaN outside a
// domain mask. The Python side converts to the input's type.
py::array_t<double> decodeValues(const PyModel& m, const py::object& shape) {
  return translated([&] {
    DecodeGrid grid = defaultDecodeGrid(*m.model);
    if (!shape.is_none()) {
      const auto s = shape.cast<std::vector<std::int64_t>>();
      if (s.size() != 3) throw py::value_error("shape must be (nz, ny, nx)");
      grid = decodeGridWithSamples(*m.model, {s[2], s[1], s[0]});
    }
    const std::int64_t count = grid.dims[0] * grid.dims[1] * grid.dims[2];
    requireMemory(8 * count, "decoding the model");
    py::array_t<double> out({grid.dims[2], grid.dims[1], grid.dims[0]});
    double* dst = out.mutable_data();
    const std::int64_t plane = grid.dims[0] * grid.dims[1];
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
  app::LoadedScene scene;
  if (py::isinstance<PyModel>(input)) {
    if (spec.method != ReconstructionMethod::Mfa)
      throw py::value_error("a model renders with method 'mfa'; grid methods need the array");
    scene = app::sceneOfModel(*input.cast<const PyModel&>().model, "model");
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
  const auto address = static_cast<std::uintptr_t>(std::stoull(text.substr(1, end - 1), nullptr, 16));
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
          "info", [](const PyModel& self) { return toPython(app::modelInfoJson(*self.model, "", 0)); },
          "The model's description (the CLI's `info --json`)")
      .def_property_readonly(
          "sample_type",
          [](const PyModel& self) { return self.model->provenance().sampleType; },
          "The input's sample type (uint8, int16, float32, ...), the default dtype of decode")
      .def("save",
           [](const PyModel& self, const std::string& path) {
             translated([&] {
               saveModel(*self.model, path);
               return 0;
             });
           },
           py::arg("path"), "Writes the model to a .mfa file (atomically)")
      .def("query", &query, py::arg("points"), py::arg("derivatives") = 0, py::arg("threads") = 0,
           "Values (N,), with derivatives=1 (N, 4) value, dx, dy, dz; with 2 (N, 10) adding "
           "dxx, dxy, dxz, dyy, dyz, dzz; points an (N, 3) array of physical x, y, z; threads: "
           "0 for all cores")
      .def("__call__",
           [](const PyModel& self, const py::object& points) { return query(self, points, 0, 0); },
           py::arg("points"), "The values at (N, 3) points")
      .def("_decode_values", &decodeValues, py::arg("shape") = py::none())
      .def(
          "_into_vtk",
          [](const PyModel& self, const py::object& data) { vtkModelData(data)->SetModel(self.model); },
          py::arg("data"))
      .def_static(
          "_from_vtk",
          [](const py::object& data) {
            const std::shared_ptr<const Model>& model = vtkModelData(data)->GetModel();
            if (!model) throw py::value_error("the vtkMFAModelData holds no model");
            return PyModel{model, nullptr};
          },
          py::arg("data"));

  m.def("_encode", &encodeArray, py::arg("array"), py::arg("spacing") = py::none(),
        py::arg("origin") = py::none());
  m.def("_encode_points", &encodePoints, py::arg("points"), py::arg("values"));
  m.def(
      "load",
      [](const std::string& path) {
        return translated([&] {
          return PyModel{std::make_shared<Model>(loadModel(path)), nullptr};
        });
      },
      py::arg("path"), "Reads a .mfa model file");
  m.def("_render", &render, py::arg("input"), py::arg("size") = py::none(),
        py::arg("spacing") = py::none(), py::arg("origin") = py::none(),
        py::arg("method") = "mfa", py::arg("alpha") = false, py::arg("float") = false);
}
