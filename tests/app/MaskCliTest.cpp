// `info` and `query` on a model with a domain mask (written here through the core library, as
// the scattered encoder would).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "TestSupport.h"
#include "app/CliRunner.h"
#include "core/model/ModelFile.h"

namespace mfadvr {
namespace {

// A trilinear model over [0,2] x [0,1] x [0,1] with value x, masked to x <= 1.
Model halfMaskedModel() {
  std::array<KnotVector, 3> knots;
  for (auto& k : knots) k = KnotVector::clampedUniform(1, 2);
  const std::vector<float> ctrl = {0, 2, 0, 2, 0, 2, 0, 2};
  Provenance p;
  p.source = "cloud.csv";
  p.inputPoints = 1000;
  p.fieldAssociation = "point data";
  p.sampleType = "float64";
  Model m(TensorBSpline(knots, ctrl), DomainBox{Vec3d(0, 0, 0), Vec3d(2, 1, 1)}, 0.0, 2.0, p);
  const std::vector<std::uint8_t> nodes = {1, 0, 1, 0, 1, 0, 1, 0};  // x = 0 face
  m.setMask(DomainMask(MaskKind::PointCoverage, {2, 2, 2}, nodes));
  return m;
}

// The half-masked model and the same model without its mask, as files in `dir`.
std::pair<std::string, std::string> writeMaskedAndPlain(const std::filesystem::path& dir) {
  const std::string masked = (dir / "masked.mfa").string(), plain = (dir / "plain.mfa").string();
  saveModel(halfMaskedModel(), masked);
  Model unmasked = halfMaskedModel();
  unmasked.setMask(DomainMask());
  saveModel(unmasked, plain);
  return {masked, plain};
}

TEST(MaskCli, InfoReportsTheMask) {
  const auto dir = test::scratchDir();
  const auto [masked, plain] = writeMaskedAndPlain(dir);

  auto r = test::runMfadvr("info " + masked + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format_version"], 3);
  EXPECT_EQ(j["mask"]["kind"], "point-coverage");
  EXPECT_EQ(j["mask"]["dims"], nlohmann::json({2, 2, 2}));
  EXPECT_DOUBLE_EQ(j["mask"]["inside_fraction"].get<double>(), 0.5);
  EXPECT_EQ(j["provenance"]["input_points"], 1000);
  EXPECT_EQ(j["provenance"]["field_association"], "point data");
  r = test::runMfadvr("info " + masked);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("mask            point-coverage, 2 x 2 x 2 nodes, 50% inside"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("1,000 scattered points"), std::string::npos) << r.out;

  r = test::runMfadvr("info " + plain + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mask"]["kind"], "none");
  EXPECT_DOUBLE_EQ(j["mask"]["inside_fraction"].get<double>(), 1.0);
  r = test::runMfadvr("info " + plain);
  EXPECT_NE(r.out.find("mask            none"), std::string::npos) << r.out;
}

TEST(MaskCli, QueryFlagsPointsOutsideTheMask) {
  const auto dir = test::scratchDir();
  const auto [masked, plain] = writeMaskedAndPlain(dir);

  std::ofstream(dir / "points.txt") << "0.5 0.5 0.5\n1.5 0.5 0.5\n1 0 1\n";
  auto r = test::runMfadvr("query " + masked + " --points " + (dir / "points.txt").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "x,y,z,value,inside\n0.5,0.5,0.5,0.5,1\n1.5,0.5,0.5,1.5,0\n1,0,1,1,1\n");
  EXPECT_NE(r.err.find("1 of 3 points lie outside the model's domain mask"), std::string::npos)
      << r.err;

  r = test::runMfadvr("query " + masked + " 1.5 0.5 0.5 -d 2");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream csv(r.out);
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(header, "x,y,z,value,dx,dy,dz,dxx,dxy,dxz,dyy,dyz,dzz,inside");
  EXPECT_EQ(row.substr(row.size() - 2), ",0");
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), 13);

  // Without a mask the output keeps its old columns.
  r = test::runMfadvr("query " + plain + " 1.5 0.5 0.5 -d 1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "x,y,z,value,dx,dy,dz");
  EXPECT_EQ(r.err, "");
}

}  // namespace
}  // namespace mfadvr
