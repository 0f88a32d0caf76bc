// ZFP keeps its own bit-stream functions in a process where another library, loaded first,
// defines functions of the same names (CFITSIO in every ParaView process): ZfpLibrary.h.
// This program links a decoy of those names ahead of everything else; the CLI tests run the
// command with the real CFITSIO preloaded.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "TestSupport.h"
#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "core/model/ControlCoding.h"
#include "core/model/ModelFile.h"
#include "core/model/ZfpArray.h"

extern "C" int decoy_stream_calls(void);
extern "C" int stream_open(char*, int, int*);

namespace mfadvr {
namespace {

std::vector<float> ramp(const Index3& d) {
  std::vector<float> v;
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        v.push_back(static_cast<float>(std::sin(0.2 * x) + 0.05 * y * z));
  return v;
}

// The clash is real in this process: a global lookup of ZFP's names finds the decoy.
TEST(ZfpIsolation, TheDecoyTakesTheGlobalNames) {
  EXPECT_EQ(dlsym(RTLD_DEFAULT, "stream_open"), reinterpret_cast<void*>(&stream_open));
  const int before = decoy_stream_calls();
  int handle = 0;
  stream_open(nullptr, 0, &handle);
  EXPECT_EQ(decoy_stream_calls(), before + 1);
}

TEST(ZfpIsolation, ArraysRoundTripBesideTheDecoy) {
  const int before = decoy_stream_calls();
  const Index3 d{24, 17, 9};
  const std::vector<float> v = ramp(d);
  const ZfpSettings tolerance{ZfpSettings::Mode::kAccuracy, 1e-3};
  const std::string stream = zfpCompress(v, d, tolerance);
  const std::vector<float> back = zfpDecompress(
      {reinterpret_cast<const std::uint8_t*>(stream.data()), stream.size()}, d, tolerance);
  ASSERT_EQ(back.size(), v.size());
  for (size_t i = 0; i < v.size(); ++i) ASSERT_NEAR(back[i], v[i], 1e-3) << "value " << i;
  EXPECT_EQ(decoy_stream_calls(), before);
}

// A zfp-coded model file, written and read back, evaluates as the model that was written.
TEST(ZfpIsolation, ZfpCodedModelFilesLoadBesideTheDecoy) {
  const int before = decoy_stream_calls();
  const StructuredGrid g = sampleBuiltinSpec("builtin:marschner-lobb:20x18x16");
  const Model coded = codeControlPoints(fitStructured(g, {}), {ControlCoder::kZfp, 1e-3});
  const auto path = test::scratchDir() / "zfp.mfa";
  saveModel(coded, path);
  const Model back = loadModel(path);
  EXPECT_EQ(back.controlCoding().coder, ControlCoder::kZfp);
  EXPECT_EQ(test::values(back.spline().controlPoints()),
            test::values(coded.spline().controlPoints()));
  EXPECT_EQ(decoy_stream_calls(), before);
}

}  // namespace
}  // namespace mfadvr
