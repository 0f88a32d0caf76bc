// End-to-end tests of the `mfadvr` program: exit codes, outputs, and that failures leave no
// partial output behind.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "TestSupport.h"
#include "app/CliRunner.h"

namespace mfadvr {
namespace {

using Result = test::CliResult;
using test::slurp;
Result run(const std::string& args) {
  return test::runMfadvr(args);
}

TEST(Cli, VersionAndHelp) {
  Result r = run("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("mfadvr"), std::string::npos);
  for (const char* sub : {"", "encode ", "info ", "query "}) {
    r = run(std::string(sub) + "--help");
    EXPECT_EQ(r.status, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("frobnicate").status, 2);
  EXPECT_EQ(run("encode").status, 2);                                       // missing input
  EXPECT_EQ(run("encode builtin:gaussian-beam:8 --degree 1,2").status, 2);  // two values
  EXPECT_EQ(run("encode builtin:gaussian-beam:8 --ctrl x").status, 2);
  EXPECT_EQ(run("query m.mfa --derivatives 3").status, 2);
  EXPECT_EQ(run("encode builtin:gaussian-beam:8 --degree 99999999999").status, 2);
}

TEST(Cli, EncodeInfoQueryRoundTrip) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "beam.mfa").string();
  Result r = run("encode builtin:gaussian-beam:24x20x16 --degree 3,2,3 --ctrl 12,10,8 -o " + model +
                 " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["samples"], nlohmann::json({24, 20, 16}));
  EXPECT_EQ(report["control_counts"], nlohmann::json({12, 10, 8}));
  EXPECT_EQ(report["model_bytes"].get<std::int64_t>(),
            static_cast<std::int64_t>(std::filesystem::file_size(model)));
  EXPECT_GT(report["compression_ratio"].get<double>(), 1.0);
  EXPECT_LT(report["max_relative_error"].get<double>(), 0.1);

  r = run("info " + model + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  EXPECT_EQ(info["degree"], nlohmann::json({3, 2, 3}));
  EXPECT_EQ(info["provenance"]["source"], "builtin:gaussian-beam:24x20x16");
  EXPECT_EQ(run("info " + model).status, 0);

  r = run("query " + model + " 0 0 0 --derivatives 2");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream csv(r.out);
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header, "x,y,z,value,dx,dy,dz,dxx,dxy,dxz,dyy,dyz,dzz");
  double x, y, z, v;
  ASSERT_EQ(std::sscanf(row.c_str(), "%lf,%lf,%lf,%lf", &x, &y, &z, &v), 4);
  EXPECT_NEAR(v, 255.0, 255.0 * 0.05);  // beam peak at the origin

  // Curvature columns after the derivatives, k1 >= k2.
  r = run("query " + model + " 0 0 0 --curvature");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "x,y,z,value,k1,k2");
  r = run("query " + model + " 0.3 0.1 0.2 -d 1 --curvature");
  ASSERT_EQ(r.status, 0) << r.err;
  double k[2], g[3];
  ASSERT_EQ(
      std::sscanf(r.out.substr(r.out.find('\n') + 1).c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf",
                  &x, &y, &z, &v, &g[0], &g[1], &g[2], &k[0], &k[1]),
      9)
      << r.out;
  EXPECT_GE(k[0], k[1]);

  std::ofstream(dir / "points.txt") << "x,y,z\n0 0 0\n0.5, -0.25, 0.1\n\n# comment\n2 0 0\n";
  r = run("query " + model + " --points " + (dir / "points.txt").string() + " -d 1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 4);
  EXPECT_NE(r.err.find("outside"), std::string::npos);  // (2,0,0) is outside [-1,1]^3
}

TEST(Cli, FailuresExitOneWithoutPartialOutput) {
  const auto dir = test::scratchDir();
  const std::string model = (dir / "out.mfa").string();
  Result r = run("encode builtin:gaussian-beam:8 --ctrl 9 -o " + model);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("exceed"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(model));

  r = run("encode builtin:gaussian-beam:8 --ctrl 3 --degree 3 -o " + model);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("too few"), std::string::npos) << r.err;
  r = run("encode builtin:gaussian-beam:8 --degree 0 -o " + model);
  EXPECT_EQ(r.status, 1);
  r = run("encode builtin:no-such-function -o " + model);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("unknown built-in"), std::string::npos) << r.err;
  r = run("encode " + (dir / "missing.raw").string() + " -o " + model);
  EXPECT_EQ(r.status, 1);
  EXPECT_FALSE(std::filesystem::exists(model));

  std::ofstream(dir / "junk.mfa") << "this is not a model";
  r = run("info " + (dir / "junk.mfa").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("not an .mfa model"), std::string::npos) << r.err;
  r = run("query " + (dir / "junk.mfa").string() + " 0 0 0");
  EXPECT_EQ(r.status, 1);

  ASSERT_EQ(run("encode builtin:gaussian-beam:8 -o " + model).status, 0);
  std::ofstream(dir / "bad.txt") << "0 0 0\n1 2\n";
  const std::string csv = (dir / "q.csv").string();
  r = run("query " + model + " --points " + (dir / "bad.txt").string() + " -o " + csv);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("line 2"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(csv));
  // Only the intended files remain: no temporaries from the atomic writes.
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
}

}  // namespace
}  // namespace mfadvr
