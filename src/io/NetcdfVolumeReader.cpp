#include "io/NetcdfVolumeReader.h"

#include <netcdf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

#include "core/util/Error.h"
#include "io/InputFile.h"
#include "io/headers/HeaderText.h"

namespace mfadvr {
namespace {

using headers::lower;

// An open file, closed when it goes.
class NetcdfFile {
 public:
  explicit NetcdfFile(const std::string& path) : path_(path) {
    check(nc_open(path.c_str(), NC_NOWRITE, &id_), "cannot open it");
  }
  ~NetcdfFile() {
    if (id_ >= 0) nc_close(id_);
  }
  NetcdfFile(const NetcdfFile&) = delete;
  NetcdfFile& operator=(const NetcdfFile&) = delete;
  int id() const { return id_; }

  void check(int status, const std::string& what) const {
    if (status != NC_NOERR)
      throw Error("cannot read " + path_ + " as NetCDF: " + what + " (" + nc_strerror(status) +
                  ")");
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw Error("cannot read " + path_ + " as NetCDF: " + why);
  }

  // A text attribute of `var` (NC_GLOBAL for the file's), or nullopt.
  std::optional<std::string> text(int var, const char* name) const {
    nc_type type = 0;
    size_t length = 0;
    if (nc_inq_att(id_, var, name, &type, &length) != NC_NOERR || type != NC_CHAR) return {};
    if (length > (1 << 20)) return {};
    std::string s(length, '\0');
    if (nc_get_att_text(id_, var, name, s.data()) != NC_NOERR) return {};
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
      s.pop_back();
    return s;
  }
  // A numeric attribute's first value, or nullopt.
  std::optional<double> number(int var, const char* name) const {
    nc_type type = 0;
    size_t length = 0;
    if (nc_inq_att(id_, var, name, &type, &length) != NC_NOERR || length < 1 || type == NC_CHAR ||
        type == NC_STRING)
      return {};
    std::vector<double> v(length);
    if (nc_get_att_double(id_, var, name, v.data()) != NC_NOERR) return {};
    return v[0];
  }

 private:
  std::string path_;
  int id_ = -1;
};

struct Variable {
  int id = -1;
  std::string name;
  nc_type type = 0;
  std::vector<int> dims;
};

Variable variable(const NetcdfFile& f, int id) {
  char name[NC_MAX_NAME + 1] = {};
  int ndims = 0, natts = 0;
  int dims[NC_MAX_VAR_DIMS] = {};
  Variable v;
  f.check(nc_inq_var(f.id(), id, name, &v.type, &ndims, dims, &natts), "its variables");
  v.id = id;
  v.name = name;
  v.dims.assign(dims, dims + ndims);
  return v;
}

std::string dimName(const NetcdfFile& f, int dim) {
  char name[NC_MAX_NAME + 1] = {};
  f.check(nc_inq_dimname(f.id(), dim, name), "its dimensions");
  return name;
}

size_t dimLength(const NetcdfFile& f, int dim) {
  size_t n = 0;
  f.check(nc_inq_dimlen(f.id(), dim, &n), "its dimensions");
  return n;
}

// The coordinate variable of a dimension: one-dimensional, named as the dimension.
std::optional<Variable> coordinateOf(const NetcdfFile& f, int dim) {
  int id = -1;
  if (nc_inq_varid(f.id(), dimName(f, dim).c_str(), &id) != NC_NOERR) return {};
  Variable v = variable(f, id);
  if (v.dims.size() != 1 || v.dims[0] != dim) return {};
  return v;
}

bool isUnlimited(const NetcdfFile& f, int dim) {
  int count = 0;
  if (nc_inq_unlimdims(f.id(), &count, nullptr) != NC_NOERR || count <= 0) return false;
  std::vector<int> ids(static_cast<size_t>(count));
  nc_inq_unlimdims(f.id(), &count, ids.data());
  return std::find(ids.begin(), ids.end(), dim) != ids.end();
}

// CF's ways of saying that a dimension is time.
bool isTimeDimension(const NetcdfFile& f, int dim) {
  if (const auto c = coordinateOf(f, dim)) {
    if (const auto axis = f.text(c->id, "axis")) return lower(*axis) == "t";
    if (const auto name = f.text(c->id, "standard_name"); name && lower(*name) == "time")
      return true;
    if (const auto units = f.text(c->id, "units");
        units && lower(*units).find(" since ") != std::string::npos)
      return true;
  }
  const std::string name = lower(dimName(f, dim));
  return name == "time" || name == "t" || isUnlimited(f, dim);
}

bool isNumeric(nc_type t) {
  return t == NC_BYTE || t == NC_UBYTE || t == NC_SHORT || t == NC_USHORT || t == NC_INT ||
         t == NC_UINT || t == NC_FLOAT || t == NC_DOUBLE || t == NC_INT64 || t == NC_UINT64;
}

const char* sampleTypeOf(nc_type t) {
  switch (t) {
    case NC_BYTE:
      return "int8";
    case NC_UBYTE:
      return "uint8";
    case NC_SHORT:
      return "int16";
    case NC_USHORT:
      return "uint16";
    case NC_INT:
      return "int32";
    case NC_UINT:
      return "uint32";
    case NC_FLOAT:
      return "float32";
    default:
      return "float64";
  }
}

int typeBytes(nc_type t) {
  switch (t) {
    case NC_BYTE:
    case NC_UBYTE:
      return 1;
    case NC_SHORT:
    case NC_USHORT:
      return 2;
    case NC_INT:
    case NC_UINT:
    case NC_FLOAT:
      return 4;
    default:
      return 8;
  }
}

// How a variable's dimensions make a volume: which is time (-1: none) and which are x, y, z
// (positions in the variable's dimension list); nullopt when they do not make one.
struct Shape {
  int time = -1;
  int axis[3] = {-1, -1, -1};  // x, y, z
};
std::optional<Shape> volumeShape(const NetcdfFile& f, const Variable& v, std::string* why) {
  std::vector<int> large;  // positions of dimensions of more than one value, slowest first
  for (size_t i = 0; i < v.dims.size(); ++i)
    if (dimLength(f, v.dims[i]) > 1) large.push_back(static_cast<int>(i));
  Shape s;
  for (size_t i = 0; i < large.size(); ++i) {
    if (!isTimeDimension(f, v.dims[static_cast<size_t>(large[i])])) continue;
    if (i != 0) {
      if (why)
        *why = "its time dimension '" + dimName(f, v.dims[static_cast<size_t>(large[i])]) +
               "' is not its slowest (first) dimension";
      return {};
    }
    s.time = large[i];
  }
  const size_t spatial = large.size() - (s.time >= 0 ? 1 : 0);
  if (spatial != 3) {
    if (why)
      *why = "it has " + std::to_string(spatial) +
             " spatial dimensions of more than one value (a volume has 3)";
    return {};
  }
  for (int a = 0; a < 3; ++a) s.axis[a] = large[large.size() - 1 - static_cast<size_t>(a)];
  return s;
}

std::string describeDims(const NetcdfFile& f, const Variable& v) {
  std::string s = v.name + "(";
  for (size_t i = 0; i < v.dims.size(); ++i)
    s += (i ? ", " : "") + dimName(f, v.dims[i]) + "=" + std::to_string(dimLength(f, v.dims[i]));
  return s + ")";
}

}  // namespace

bool isNetcdfPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".nc" || ext == ".nc4" || ext == ".cdf" || ext == ".netcdf";
}

NetcdfVolume describeNetcdfVolume(const std::string& path, const FieldSelection& field) {
  requireNonEmptyFile(path, "a NetCDF file");
  if (field.association == FieldAssociation::kCells)
    throw Error(path +
                ": a NetCDF variable of a regular grid holds samples at its points, not "
                "cell data");
  if (field.component != FieldSelection::kWholeArray)
    throw Error(path +
                ": a NetCDF variable read by mfadvr holds one scalar per sample, so "
                "--component does not apply to it");
  const NetcdfFile f(path);
  int nvars = 0;
  f.check(nc_inq_nvars(f.id(), &nvars), "its variables");
  // Candidates: data variables (not coordinate variables) that make a volume.
  std::vector<std::pair<Variable, Shape>> volumes;
  std::string list;
  std::optional<Variable> named;
  std::string namedWhy;
  for (int id = 0; id < nvars; ++id) {
    Variable v = variable(f, id);
    const bool coordinate = v.dims.size() == 1 && dimName(f, v.dims[0]) == v.name;
    if (coordinate || !isNumeric(v.type)) continue;
    std::string why;
    const auto shape = volumeShape(f, v, &why);
    if (v.name == field.name) {
      named = v;
      namedWhy = why;
    }
    if (!shape) continue;
    list += (list.empty() ? "" : ", ") + describeDims(f, v);
    volumes.emplace_back(std::move(v), *shape);
  }
  const std::pair<Variable, Shape>* chosen = nullptr;
  if (!field.name.empty()) {
    for (const auto& c : volumes)
      if (c.first.name == field.name) chosen = &c;
    if (!chosen && named)
      f.fail("the variable " + describeDims(f, *named) + " is not a volume: " + namedWhy);
    if (!chosen)
      f.fail("it has no numeric variable '" + field.name + "'" +
             (list.empty() ? std::string() : "; its volumes: " + list));
  } else if (volumes.size() == 1) {
    chosen = &volumes.front();
  } else if (volumes.empty()) {
    f.fail(
        "none of its variables is a volume (three dimensions of more than one value, "
        "besides an optional time dimension first)");
  } else {
    f.fail("it holds several volumes (" + list + "): choose one with --field NAME");
  }
  const Variable& v = chosen->first;
  const Shape& shape = chosen->second;

  NetcdfVolume volume;
  volume.path = path;
  volume.variable = v.name;
  StructuredGrid& g = volume.layout;
  g.fieldName = v.name;
  g.fieldAssociation = "point data";
  g.source = path;
  for (int a = 0; a < 3; ++a) {
    const size_t n = dimLength(f, v.dims[static_cast<size_t>(shape.axis[a])]);
    if (n > static_cast<size_t>(std::numeric_limits<std::int32_t>::max()))
      f.fail("dimension '" + dimName(f, v.dims[static_cast<size_t>(shape.axis[a])]) +
             "' is too long");
    g.dims[a] = static_cast<std::int64_t>(n);
  }
  // A damaged header may declare more values than the file can hold; refused before any
  // allocation (compressed netCDF-4 data: at most 1032 bytes per stored byte, deflate's limit).
  int format = 0;
  f.check(nc_inq_format(f.id(), &format), "its format");
  const bool compressed = format == NC_FORMAT_NETCDF4 || format == NC_FORMAT_NETCDF4_CLASSIC;
  std::error_code ec;
  const double fileBytes = static_cast<double>(std::filesystem::file_size(path, ec));
  const auto requireHeld = [&](double bytes, const std::string& what) {
    if (ec || bytes > (compressed ? 1032.0 : 1.0) * fileBytes + 4096.0)
      f.fail(what + " declares more values than the file's " +
             std::to_string(static_cast<std::int64_t>(fileBytes)) +
             " bytes can hold: the file is cut short or damaged");
  };
  requireHeld(static_cast<double>(g.dims[0]) * static_cast<double>(g.dims[1]) *
                  static_cast<double>(g.dims[2]) * typeBytes(v.type),
              "variable " + describeDims(f, v));
  for (int a = 0; a < 3; ++a) {
    const int dim = v.dims[static_cast<size_t>(shape.axis[a])];
    const size_t n = dimLength(f, dim);
    g.spacing[a] = 1.0;
    g.origin[a] = 0.0;
    const char axisName = "xyz"[a];
    const auto c = coordinateOf(f, dim);
    if (!c || !isNumeric(c->type)) {
      g.notes.push_back(std::string(1, axisName) + " ('" + dimName(f, dim) +
                        "') has no coordinate variable: placed by index");
      continue;
    }
    requireHeld(static_cast<double>(n) * typeBytes(c->type), "coordinate " + c->name);
    std::vector<double> x(n);
    f.check(nc_get_var_double(f.id(), c->id, x.data()), "the coordinates of " + c->name);
    const double step = (x[n - 1] - x[0]) / static_cast<double>(n - 1);
    bool even = std::isfinite(step) && step > 0.0;
    for (size_t i = 0; even && i + 1 < n; ++i)
      even = std::isfinite(x[i + 1]) && std::abs(x[i + 1] - x[i] - step) <= 1e-4 * step;
    if (!even) {
      g.notes.push_back(std::string(1, axisName) + " ('" + c->name +
                        "'): its coordinates are not evenly spaced and increasing; placed by "
                        "index");
      continue;
    }
    g.spacing[a] = step;
    g.origin[a] = x[0];
  }
  const auto scale = f.number(v.id, "scale_factor");
  const auto offset = f.number(v.id, "add_offset");
  g.sampleType = scale || offset ? "float32" : sampleTypeOf(v.type);
  if (scale || offset) g.notes.push_back("packed values unpacked (scale_factor, add_offset)");
  g.inputBytes = g.sampleCount() * typeBytes(v.type);
  if (shape.time >= 0) {
    const int dim = v.dims[static_cast<size_t>(shape.time)];
    const size_t n = dimLength(f, dim);
    requireHeld(static_cast<double>(n), "time dimension '" + dimName(f, dim) + "'");
    volume.times.resize(n);
    const auto c = coordinateOf(f, dim);
    if (c && isNumeric(c->type)) {
      f.check(nc_get_var_double(f.id(), c->id, volume.times.data()), "the times of " + c->name);
      for (size_t s = 0; s < n; ++s)
        if (!std::isfinite(volume.times[s]))
          f.fail("time " + std::to_string(s) + " of '" + c->name + "' is not a finite number");
      if (const auto units = f.text(c->id, "units"))
        g.notes.push_back("times in " + *units + " ('" + c->name + "')");
    } else {
      for (size_t s = 0; s < n; ++s) volume.times[s] = static_cast<double>(s);
      g.notes.push_back("the time dimension '" + dimName(f, dim) +
                        "' has no coordinate variable: times 0, 1, 2, ...");
    }
  }
  return volume;
}

StructuredGrid readNetcdfStep(const NetcdfVolume& volume, int step) {
  const NetcdfFile f(volume.path);
  int id = -1;
  f.check(nc_inq_varid(f.id(), volume.variable.c_str(), &id), "variable " + volume.variable);
  const Variable v = variable(f, id);
  const auto shape = volumeShape(f, v, nullptr);
  if (!shape) f.fail("variable " + volume.variable + " changed while it was read");
  const size_t steps = volume.times.empty() ? 1 : volume.times.size();
  if (step < 0 || static_cast<size_t>(step) >= steps)
    throw Error(volume.path + ": no time step " + std::to_string(step));
  std::vector<size_t> start(v.dims.size(), 0), count(v.dims.size(), 1);
  for (int a = 0; a < 3; ++a)
    count[static_cast<size_t>(shape->axis[a])] = static_cast<size_t>(volume.layout.dims[a]);
  if (shape->time >= 0) start[static_cast<size_t>(shape->time)] = static_cast<size_t>(step);
  StructuredGrid grid = volume.layout;
  const std::int64_t n = grid.sampleCount();
  std::vector<double> raw(static_cast<size_t>(n));
  f.check(nc_get_vara_double(f.id(), id, start.data(), count.data(), raw.data()),
          "the samples of " + volume.variable +
              (shape->time >= 0 ? ", step " + std::to_string(step) : std::string()));
  // Missing data: the fill value, missing_value, and for float data netCDF's default fill.
  std::vector<double> missing;
  for (const char* name : {"_FillValue", "missing_value"})
    if (const auto m = f.number(id, name)) missing.push_back(*m);
  if (v.type == NC_FLOAT) missing.push_back(static_cast<double>(NC_FILL_FLOAT));
  if (v.type == NC_DOUBLE) missing.push_back(NC_FILL_DOUBLE);
  const double scale = f.number(id, "scale_factor").value_or(1.0);
  const double offset = f.number(id, "add_offset").value_or(0.0);
  grid.values.resize(raw.size());
  std::int64_t holes = 0;
  for (size_t i = 0; i < raw.size(); ++i) {
    const double r = raw[i];
    if (std::find(missing.begin(), missing.end(), r) != missing.end() || !std::isfinite(r)) {
      ++holes;
      continue;
    }
    grid.values[i] = static_cast<float>(r * scale + offset);
  }
  if (holes > 0) {
    std::ostringstream m;
    m << volume.path << ": " << holes << " of the " << n << " samples of " << volume.variable
      << (shape->time >= 0 ? " at step " + std::to_string(step) : std::string())
      << " are missing (fill values or not finite); mfadvr needs a value at every sample";
    throw Error(m.str());
  }
  return grid;
}

StructuredGrid readNetcdfVolume(const std::string& path, const FieldSelection& field) {
  NetcdfVolume volume = describeNetcdfVolume(path, field);
  StructuredGrid grid = readNetcdfStep(volume, 0);
  if (volume.times.size() > 1)
    grid.notes.push_back("holds " + std::to_string(volume.times.size()) +
                         " time steps: the first is read (`mfadvr encode` makes one 4-D model "
                         "of them all)");
  return grid;
}

}  // namespace mfadvr
