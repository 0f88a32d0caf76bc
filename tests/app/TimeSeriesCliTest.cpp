// Time series end to end: `encode` of numbered files, collections and time-varying built-ins into
// one 4-D model, then `info`, `decode --time`, `query` in time and `render --time/--times`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

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
  fails(pattern + " --max-error 1e-3", "not available for time series");
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
