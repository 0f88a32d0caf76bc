// Time series end to end: `encode` of numbered files, collections and time-varying built-ins into
// one 4-D model, then `info`, `decode --time`, `query` in time and `render --time/--times`.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "GzipBytes.h"
#include "TestSupport.h"
#include "app/CliRunner.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;
using test::runMfadvr;

constexpr int kNx = 12, kNy = 10, kNz = 8;

// An 8-bit blob moving along x: step s has its centre at x = 3 + s.
std::vector<std::uint8_t> stepValues(int s, int nz = kNz) {
  std::vector<std::uint8_t> v;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < kNy; ++y)
      for (int x = 0; x < kNx; ++x) {
        const double dx = x - 3.0 - s, dy = y - 4.5, dz = z - 3.5;
        v.push_back(static_cast<std::uint8_t>(
            std::lround(220.0 * std::exp(-(dx * dx + dy * dy + dz * dz) / 8.0))));
      }
  return v;
}

void writeNrrd(const fs::path& path, const std::vector<std::uint8_t>& v, int nz = kNz) {
  std::ofstream out(path, std::ios::binary);
  out << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: " << kNx << " " << kNy << " " << nz
      << "\nencoding: raw\n\n";
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size()));
}

// frame_000.nrrd .. frame_004.nrrd in `dir`.
void writeFrames(const fs::path& dir, int steps = 5) {
  for (int s = 0; s < steps; ++s) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%03d.nrrd", s);
    writeNrrd(dir / name, stepValues(s));
  }
}

nlohmann::json jsonOf(const test::CliResult& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "): " << r.out << r.err;
    return {};
  }
}

TEST(TimeSeriesCli, NumberedFilesBecomeOneModelThatDecodesBackEveryStep) {
  const fs::path dir = test::scratchDir();
  writeFrames(dir);
  const std::string model = (dir / "series.mfa").string();
  const auto r =
      runMfadvr("encode '" + (dir / "frame_%03d.nrrd").string() + "' --json -q -o " + model);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = jsonOf(r);
  EXPECT_EQ(j["time"]["steps"], 5);
  EXPECT_EQ(j["time"]["degree"], 3);
  EXPECT_EQ(j["time"]["control_count"], 5);
  EXPECT_EQ(j["coding"]["method"], "zfp");
  EXPECT_LE(j["max_error"].get<double>(), 0.5);

  const auto info = runMfadvr("info --json " + model);
  ASSERT_EQ(info.status, 0) << info.err;
  const auto ij = jsonOf(info);
  EXPECT_EQ(ij["format_version"], 4);
  EXPECT_EQ(ij["time"]["steps"], nlohmann::json({0.0, 1.0, 2.0, 3.0, 4.0}));
  EXPECT_TRUE(ij["time"]["uniform_steps"].get<bool>());
  EXPECT_NE(runMfadvr("info " + model).out.find("5 steps, t = 0 .. 4"), std::string::npos);

  // Every step rounds back to its samples.
  for (int s : {0, 2, 4}) {
    const std::string out = (dir / ("back" + std::to_string(s) + ".raw")).string();
    const auto d = runMfadvr("decode " + model + " --time " + std::to_string(s) + " -q -o " + out);
    ASSERT_EQ(d.status, 0) << d.err;
    const std::string back = test::slurp(out);
    const auto expected = stepValues(s);
    ASSERT_EQ(back.size(), expected.size());
    EXPECT_EQ(std::memcmp(back.data(), expected.data(), expected.size()), 0) << "step " << s;
  }
  // The folder holding the frames is the same series.
  const auto folder = runMfadvr("encode " + dir.string() + " --json -q");
  ASSERT_EQ(folder.status, 0) << folder.err;
  EXPECT_EQ(jsonOf(folder)["time"]["steps"], 5);
  EXPECT_EQ(runMfadvr("decode " + model + " --time 9 -q -o " + (dir / "x.raw").string()).status, 1);

  // --dequantize, --max-error and budgets apply to the 4-D model; a dequantized one still decodes
  // back to every sample.
  const std::string pattern = "'" + (dir / "frame_%03d.nrrd").string() + "'";
  const std::string smooth = (dir / "smooth.mfa").string();
  const auto dq = runMfadvr("encode " + pattern + " --dequantize --json -q -o " + smooth);
  ASSERT_EQ(dq.status, 0) << dq.err;
  EXPECT_EQ(jsonOf(dq)["encoder"], "time-series-dequantize");
  EXPECT_LT(jsonOf(dq)["max_error"].get<double>(), 0.5);
  const std::string out = (dir / "smooth3.raw").string();
  ASSERT_EQ(runMfadvr("decode " + smooth + " --time 3 -q -o " + out).status, 0);
  EXPECT_EQ(test::slurp(out),
            std::string(reinterpret_cast<const char*>(stepValues(3).data()), stepValues(3).size()));
  const auto ad = runMfadvr("encode " + pattern + " --max-error 0.05 --strict --json -q");
  ASSERT_EQ(ad.status, 0) << ad.err;
  EXPECT_GE(jsonOf(ad)["adaptive"]["history"].size(), 1u);
  EXPECT_EQ(jsonOf(ad)["encoder"], "time-series-least-squares-adaptive");
  const auto budget = runMfadvr("encode " + pattern + " --psnr 35 --json -q");
  ASSERT_EQ(budget.status, 0) << budget.err;
  EXPECT_GE(jsonOf(budget)["psnr"].get<double>(), 35.0);
}

TEST(TimeSeriesCli, CollectionsGiveTheirTimes) {
  const fs::path dir = test::scratchDir();
  writeFrames(dir, 4);
  {
    std::ofstream pvd(dir / "run.pvd");
    pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "  <Collection>\n";
    const double times[] = {0.0, 0.5, 0.75, 2.0};
    for (int s = 0; s < 4; ++s)
      pvd << "    <DataSet timestep=\"" << times[s] << "\" group=\"\" part=\"0\" file=\"frame_00"
          << s << ".nrrd\"/>\n";
    pvd << "  </Collection>\n</VTKFile>\n";
  }
  const std::string model = (dir / "pvd.mfa").string();
  ASSERT_EQ(runMfadvr("encode " + (dir / "run.pvd").string() + " -q -o " + model).status, 0);
  const auto ij = jsonOf(runMfadvr("info --json " + model));
  EXPECT_EQ(ij["time"]["steps"], nlohmann::json({0.0, 0.5, 0.75, 2.0}));
  EXPECT_FALSE(ij["time"]["uniform_steps"].get<bool>());
  {
    std::ofstream series(dir / "run.series");
    series << R"({"file-series-version": "1.0", "files": [{"name": "frame_000.nrrd", "time": 1},
      {"name": "frame_001.nrrd", "time": 2}, {"name": "frame_002.nrrd", "time": 4}]})";
  }
  const auto s = runMfadvr("encode " + (dir / "run.series").string() + " -q --json");
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_EQ(jsonOf(s)["time"]["steps"], 3);
  EXPECT_EQ(jsonOf(s)["time"]["degree"], 2);  // lowered: three steps
  // --times replaces the numbers of a pattern.
  const auto t = runMfadvr("encode '" + (dir / "frame_%03d.nrrd").string() +
                           "' --times 0,0.1,0.3,0.4 -q -o " + model);
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(jsonOf(runMfadvr("info --json " + model))["time"]["range"], nlohmann::json({0.0, 0.4}));
}

TEST(TimeSeriesCli, BadSeriesAreClearErrorsAndWriteNothing) {
  const fs::path dir = test::scratchDir();
  writeFrames(dir, 5);
  const std::string model = (dir / "bad.mfa").string();
  // Quoted for the shell, appended piece by piece (GCC 12's -Wrestrict misreads "'" + string).
  auto quoted = [](const fs::path& p) {
    std::string q = "'";
    q += p.string();
    q += "'";
    return q;
  };
  const std::string pattern = quoted(dir / "frame_%03d.nrrd");
  auto fails = [&](const std::string& args, const std::string& message) {
    const auto r = runMfadvr("encode " + args + " -q -o " + model);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(model)) << args;
  };
  fails(pattern + " --times 0,1,2", "3 times for the 5 steps");
  fails(pattern + " --times 0,1,3,2,4", "must increase");
  fails(pattern + " --time-ctrl 9", "--time-ctrl 9");
  fails(pattern + " --max-error 1e-3 --time-ctrl 4", "interpolates in time");
  fails(pattern + " --dequantize 0.5 --time-ctrl 4", "interpolates in time");
  fails(pattern + " --psnr 40 --coding lossless", "needs --coding zfp");
  fails(pattern + " --strict", "give --max-error too");
  fails(pattern + " --blocks 2", "does not apply to time series");
  fails("builtin:marschner-lobb:8 --time-ctrl 3", "apply to time series");
  // A step on another grid, named.
  writeNrrd(dir / "frame_003.nrrd", stepValues(3, kNz + 1), kNz + 1);
  fails(pattern, "frame_003.nrrd has another grid");
  // A missing step, named.
  fs::remove(dir / "frame_003.nrrd");
  fails(pattern, "step 3 is missing");
  fails(quoted(dir / "none_%03d.nrrd"), "no file matches");
  {
    std::ofstream pvd(dir / "gone.pvd");
    pvd << "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\" "
           "file=\"frame_000.nrrd\"/>"
           "<DataSet timestep=\"1\" file=\"lost.nrrd\"/></Collection></VTKFile>";
  }
  fails((dir / "gone.pvd").string(), "lost.nrrd) does not exist");
}

// Two time-varying models give the same values, float for float, at a step (1.5) and between
// steps (2.25): decoded on their grid in scratch files of `dir`.
void expectSameInstants(const std::string& model, const std::string& reference,
                        const fs::path& dir) {
  for (const char* t : {"1.5", "2.25"}) {
    const std::string a = (dir / "a.raw").string(), b = (dir / "b.raw").string();
    ASSERT_EQ(runMfadvr("decode " + model + " --time " + t + " --type float32 -q -o " + a).status,
              0);
    ASSERT_EQ(
        runMfadvr("decode " + reference + " --time " + t + " --type float32 -q -o " + b).status, 0);
    EXPECT_EQ(test::slurp(a), test::slurp(b)) << "t = " << t;
  }
}

// All steps' samples one after another, as 4-D files store them.
std::string allSteps(int steps) {
  std::string bytes;
  for (int s = 0; s < steps; ++s) {
    const auto v = stepValues(s);
    bytes.append(reinterpret_cast<const char*>(v.data()), v.size());
  }
  return bytes;
}

// A NIfTI-1 image of uint8 samples with `steps` time points (dim[4]), pixdim[4] `dt`, toffset
// `t0`, units mm and ms; its samples gzip-coded for a .nii.gz name.
void writeNifti(const fs::path& path, int steps, float dt, float t0) {
  std::string bytes(352, '\0');
  auto put = [&](size_t at, auto value) { std::memcpy(bytes.data() + at, &value, sizeof value); };
  put(0, std::int32_t{348});
  const std::int16_t dim[8] = {4, kNx, kNy, kNz, static_cast<std::int16_t>(steps), 1, 1, 1};
  for (int d = 0; d < 8; ++d) put(40 + 2 * size_t(d), dim[d]);
  put(70, std::int16_t{2});  // DT_UINT8
  put(72, std::int16_t{8});
  const float pixdim[8] = {1.0f, 1.0f, 1.0f, 1.0f, dt, 1.0f, 1.0f, 1.0f};
  for (int d = 0; d < 8; ++d) put(76 + 4 * size_t(d), pixdim[d]);
  put(108, 352.0f);        // vox_offset
  put(123, char{2 | 16});  // xyzt_units: mm, ms
  put(136, t0);            // toffset
  std::memcpy(bytes.data() + 344, "n+1\0", 4);
  bytes += allSteps(steps);
  std::ofstream out(path, std::ios::binary);
  if (path.string().ends_with(".gz")) bytes = test::gzipBytes(bytes);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST(TimeSeriesCli, FourDimensionalNrrdAndNiftiFilesAreSeries) {
  const fs::path dir = test::scratchDir();
  writeFrames(dir);
  const std::string reference = (dir / "frames.mfa").string();
  ASSERT_EQ(runMfadvr("encode '" + (dir / "frame_%03d.nrrd").string() +
                      "' --times 1,1.5,2,2.5,3 -q -o " + reference)
                .status,
            0);
  const std::string header = "NRRD0004\ntype: uint8\ndimension: 4\nsizes: " + std::to_string(kNx) +
                             " " + std::to_string(kNy) + " " + std::to_string(kNz) +
                             " 5\nkinds: space space space time\nspacings: nan nan nan 0.5\n"
                             "axis mins: nan nan nan 1\n";
  const std::string raw = allSteps(5);
  {
    std::ofstream(dir / "run.nrrd", std::ios::binary) << header << "encoding: raw\n\n" << raw;
    std::ofstream(dir / "runz.nrrd", std::ios::binary) << header << "encoding: gzip\n\n"
                                                       << test::gzipBytes(raw);
  }
  writeNifti(dir / "run.nii", 5, 0.5f, 1.0f);
  writeNifti(dir / "run.nii.gz", 5, 0.5f, 1.0f);
  for (const char* name : {"run.nrrd", "runz.nrrd", "run.nii", "run.nii.gz"}) {
    SCOPED_TRACE(name);
    const std::string model = (dir / (std::string(name) + ".mfa")).string();
    const auto e = runMfadvr("encode " + (dir / name).string() + " --json -q -o " + model);
    ASSERT_EQ(e.status, 0) << e.err;
    EXPECT_EQ(jsonOf(e)["time"]["steps"], 5);
    const auto ij = jsonOf(runMfadvr("info --json " + model));
    EXPECT_EQ(ij["time"]["steps"], nlohmann::json({1.0, 1.5, 2.0, 2.5, 3.0}));
    // The same samples at the same times as the numbered files: the same model, value for
    // value, at any instant.
    expectSameInstants(model, reference, dir);
  }
  // --times replaces the file's times; a time axis that is not the last is refused with advice.
  const auto t = runMfadvr("encode " + (dir / "run.nrrd").string() + " --times 0,1,2,4,8 -q -o " +
                           (dir / "t.mfa").string());
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(jsonOf(runMfadvr("info --json " + (dir / "t.mfa").string()))["time"]["range"],
            nlohmann::json({0.0, 8.0}));
  std::ofstream(dir / "first.nrrd", std::ios::binary)
      << "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 5 " << kNx << " " << kNy << " " << kNz
      << "\nkinds: time space space space\nencoding: raw\n\n"
      << raw;
  const auto f = runMfadvr("encode " + (dir / "first.nrrd").string() + " -q -o " +
                           (dir / "first.mfa").string());
  EXPECT_EQ(f.status, 1);
  EXPECT_NE(f.err.find("unu permute -p 1 2 3 0"), std::string::npos) << f.err;
  EXPECT_FALSE(fs::exists(dir / "first.mfa"));
  // A file cut short: nothing written.
  std::ofstream(dir / "cut.nrrd", std::ios::binary) << header << "encoding: raw\n\n"
                                                    << raw.substr(0, raw.size() - 100);
  const auto c =
      runMfadvr("encode " + (dir / "cut.nrrd").string() + " -q -o " + (dir / "cut.mfa").string());
  EXPECT_EQ(c.status, 1);
  EXPECT_FALSE(fs::exists(dir / "cut.mfa"));
}

// A CF NetCDF file: density(time, z, y, x) of the five steps as float, coordinates x = 0, 1, ...
// (and y, z), times 1, 1.5, ... in "seconds since 2000-01-01"; `extra` adds a second volume and
// `hole` puts a fill value into step 3.
void writeNetcdf(const fs::path& path, bool extra = false, bool hole = false) {
  int nc = -1, dims[4], var = -1;
  ASSERT_EQ(nc_create(path.c_str(), NC_CLOBBER, &nc), NC_NOERR);
  const char* names[4] = {"time", "z", "y", "x"};
  const size_t sizes[4] = {NC_UNLIMITED, kNz, kNy, kNx};
  int coords[4];
  for (int d = 0; d < 4; ++d) {
    nc_def_dim(nc, names[d], sizes[d], &dims[d]);
    nc_def_var(nc, names[d], NC_DOUBLE, 1, &dims[d], &coords[d]);
  }
  nc_put_att_text(nc, coords[0], "units", 27, "seconds since 2000-01-01 0");
  nc_def_var(nc, "density", NC_FLOAT, 4, dims, &var);
  const float fill = -999.0f;
  nc_put_att_float(nc, var, "_FillValue", NC_FLOAT, 1, &fill);
  int other = -1;
  if (extra) nc_def_var(nc, "pressure", NC_FLOAT, 4, dims, &other);
  ASSERT_EQ(nc_enddef(nc), NC_NOERR);
  for (int d = 1; d < 4; ++d) {
    std::vector<double> c(sizes[d]);
    for (size_t i = 0; i < c.size(); ++i) c[i] = static_cast<double>(i);
    nc_put_var_double(nc, coords[d], c.data());
  }
  for (size_t s = 0; s < 5; ++s) {
    const double t = 1.0 + 0.5 * static_cast<double>(s);
    nc_put_var1_double(nc, coords[0], &s, &t);
    const auto v = stepValues(static_cast<int>(s));
    std::vector<float> f(v.begin(), v.end());
    if (hole && s == 3) f[7] = fill;
    const size_t start[4] = {s, 0, 0, 0}, count[4] = {1, kNz, kNy, kNx};
    ASSERT_EQ(nc_put_vara_float(nc, var, start, count, f.data()), NC_NOERR);
    if (extra) nc_put_vara_float(nc, other, start, count, f.data());
  }
  ASSERT_EQ(nc_close(nc), NC_NOERR);
}

TEST(TimeSeriesCli, NetcdfVariablesWithATimeAxisAreSeries) {
  const fs::path dir = test::scratchDir();
  writeFrames(dir);
  const std::string reference = (dir / "frames.mfa").string();
  ASSERT_EQ(runMfadvr("encode '" + (dir / "frame_%03d.nrrd").string() +
                      "' --times 1,1.5,2,2.5,3 --coding float32 -q -o " + reference)
                .status,
            0);
  writeNetcdf(dir / "run.nc");
  const std::string model = (dir / "nc.mfa").string();
  const auto e = runMfadvr("encode " + (dir / "run.nc").string() + " --coding float32 -o " + model);
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_NE(e.err.find("times in seconds since 2000-01-01"), std::string::npos) << e.err;
  const auto ij = jsonOf(runMfadvr("info --json " + model));
  EXPECT_EQ(ij["time"]["steps"], nlohmann::json({1.0, 1.5, 2.0, 2.5, 3.0}));
  expectSameInstants(model, reference, dir);
  // As one volume (render, or encode of a variable without time): the first step.
  const std::string png = (dir / "first.png").string();
  const auto r = runMfadvr("render " + (dir / "run.nc").string() +
                           " --method trilinear --size 24x24 -o " + png);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("holds 5 time steps: the first is read"), std::string::npos) << r.err;

  // Two volumes: --field chooses, else a clear error that lists them.
  writeNetcdf(dir / "two.nc", true);
  const auto two = runMfadvr("encode " + (dir / "two.nc").string() + " -q -o " + model + "2");
  EXPECT_EQ(two.status, 1);
  EXPECT_NE(two.err.find("several volumes (density(time=5, z=8, y=10, x=12), pressure("),
            std::string::npos)
      << two.err;
  EXPECT_NE(two.err.find("--field NAME"), std::string::npos);
  const auto chosen = runMfadvr("encode " + (dir / "two.nc").string() +
                                " --field pressure -q --json -o " + model + "2");
  ASSERT_EQ(chosen.status, 0) << chosen.err;
  EXPECT_EQ(jsonOf(chosen)["time"]["steps"], 5);
  const auto unknown =
      runMfadvr("encode " + (dir / "two.nc").string() + " --field speed -q -o " + model + "3");
  EXPECT_EQ(unknown.status, 1);
  EXPECT_NE(unknown.err.find("no numeric variable 'speed'"), std::string::npos) << unknown.err;
  EXPECT_FALSE(fs::exists(model + "3"));
  // Missing data is named; a file cut short is an error (libnetcdf's; it does not see a
  // classic file cut inside its last record, which it reads as zeros); nothing is written.
  writeNetcdf(dir / "hole.nc", false, true);
  const auto hole = runMfadvr("encode " + (dir / "hole.nc").string() + " -q -o " + model + "3");
  EXPECT_EQ(hole.status, 1);
  EXPECT_NE(hole.err.find("1 of the 960 samples of density at step 3 are missing"),
            std::string::npos)
      << hole.err;
  const std::string whole = test::slurp(dir / "run.nc");
  for (size_t keep : {size_t{100}, whole.size() / 2}) {
    std::ofstream(dir / "cut.nc", std::ios::binary) << whole.substr(0, keep);
    const auto cut = runMfadvr("encode " + (dir / "cut.nc").string() + " -q -o " + model + "3");
    EXPECT_EQ(cut.status, 1) << keep << ": " << cut.err;
    EXPECT_FALSE(fs::exists(model + "3")) << keep;
  }
}

TEST(TimeSeriesCli, BuiltinSeriesRenderQueryAndDecodeAtAnyTime) {
  const fs::path dir = test::scratchDir();
  const std::string model = (dir / "blobs.mfa").string();
  const auto e = runMfadvr("encode builtin:orbiting-blobs:16x16x16x6 -q --json -o " + model);
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_EQ(jsonOf(e)["time"]["steps"], 6);
  EXPECT_EQ(jsonOf(e)["coding"]["method"], "float32");

  const std::string png = (dir / "mid.png").string();
  const auto r = runMfadvr("render " + model + " --time 0.5 --size 48x48 -q --json -o " + png);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(jsonOf(r)["time"], 0.5);
  EXPECT_TRUE(fs::exists(png));
  // The truth of a time-varying built-in at that instant renders too.
  ASSERT_EQ(runMfadvr("render " + model + " --time 0.3 --method truth --size 32x32 -q -o " +
                      (dir / "truth.png").string())
                .status,
            0);
  const auto anim = runMfadvr("render " + model + " --times 0:1:3 --size 32x32 -q --json -o '" +
                              (dir / "f_%02d.png").string() + "'");
  ASSERT_EQ(anim.status, 0) << anim.err;
  EXPECT_EQ(jsonOf(anim)["frames"].size(), 3u);
  for (const char* f : {"f_00.png", "f_01.png", "f_02.png"}) EXPECT_TRUE(fs::exists(dir / f));
  EXPECT_EQ(runMfadvr("render " + model + " --times 0:1:3 --size 32x32 -q -o " +
                      (dir / "nopattern.png").string())
                .status,
            2);
  EXPECT_EQ(runMfadvr("render " + model + " --time 3 --size 32x32 -q -o " + png).status, 1);
  // A video of the animation, through ffmpeg (installed by scripts/install-deps.sh).
  const std::string video = (dir / "blobs.mp4").string();
  if (std::system("command -v ffmpeg > /dev/null") == 0) {
    const auto v =
        runMfadvr("render " + model + " --times 0:1:5 --size 33x24 -q --json --video " + video);
    ASSERT_EQ(v.status, 0) << v.err;
    EXPECT_EQ(jsonOf(v)["frames"].size(), 5u);
    EXPECT_EQ(test::slurp(video).substr(4, 4), "ftyp");  // an MP4 file
    const std::string gif = (dir / "blobs.gif").string();
    ASSERT_EQ(runMfadvr("render " + model + " --times 0:1:3 --size 32x32 -q --video " + gif +
                        " -o '" + (dir / "v_%d.png").string() + "'")
                  .status,
              0);
    EXPECT_EQ(test::slurp(gif).substr(0, 3), "GIF");
    EXPECT_TRUE(fs::exists(dir / "v_2.png"));
  } else {
    ADD_FAILURE() << "ffmpeg is not installed (scripts/install-deps.sh installs it): --video "
                     "not tested";
  }
  const auto noFfmpeg = runMfadvr(
      "render " + model + " --times 0:1:3 --size 32x32 -q --video " + (dir / "none.mp4").string(),
      "MFADVR_FFMPEG=/nonexistent/ffmpeg");
  EXPECT_EQ(noFfmpeg.status, 1);
  EXPECT_NE(noFfmpeg.err.find("--video needs ffmpeg"), std::string::npos) << noFfmpeg.err;
  EXPECT_FALSE(fs::exists(dir / "none.mp4"));
  EXPECT_EQ(runMfadvr("render " + model + " --size 32x32 -q --video " + video).status, 2);
  EXPECT_EQ(
      runMfadvr("render " + model + " --times 0:1:3 -q --video " + (dir / "x.ogg").string()).status,
      1);
  EXPECT_EQ(
      runMfadvr("render builtin:marschner-lobb:8 --time 0.5 --size 32x32 -q -o " + png).status, 1);

  // Query at points with their times; --derivatives 1 adds dt.
  const auto q = runMfadvr("query " + model + " 0.5 0 0 0.25 -d 1");
  ASSERT_EQ(q.status, 0) << q.err;
  EXPECT_EQ(q.out.substr(0, q.out.find('\n')), "x,y,z,t,value,dx,dy,dz,dt");
  {
    std::ofstream pts(dir / "pts.txt");
    pts << "0 0.5 0 0\n0 0.5 0 0.5\n0.5 0 0 1\n";
  }
  const auto qp = runMfadvr("query " + model + " --points " + (dir / "pts.txt").string());
  ASSERT_EQ(qp.status, 0) << qp.err;
  EXPECT_EQ(std::count(qp.out.begin(), qp.out.end(), '\n'), 4);
  const auto qt = runMfadvr("query " + model + " 0.5 0 0 --time 0.25 -d 1");
  ASSERT_EQ(qt.status, 0) << qt.err;
  EXPECT_EQ(qt.out, q.out);
  EXPECT_EQ(runMfadvr("query " + model + " 0.5 0 0").status, 2);
  const auto h = runMfadvr("query " + model + " 0.5 0 0 0.25 -d 2 --curvature");
  ASSERT_EQ(h.status, 0) << h.err;
  EXPECT_NE(h.out.find("dxx"), std::string::npos);

  const std::string nrrd = (dir / "t.nrrd").string();
  ASSERT_EQ(runMfadvr("decode " + model + " --time 0.7 -q -o " + nrrd).status, 0);
  EXPECT_TRUE(fs::exists(nrrd));
}

}  // namespace
}  // namespace mfadvr
