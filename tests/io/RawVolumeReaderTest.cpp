// Raw volumes named NAME_XxYxZ_TYPE.raw: name parsing, every sample type, size and name errors.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "core/grid/SampleRange.h"
#include "core/util/Error.h"
#include "io/RawVolumeReader.h"
#include "io/VolumeLoader.h"

namespace mfadvr {
namespace {

using test::expectError;

template <typename T>
std::string writeRaw(const std::filesystem::path& dir, const std::string& name,
                     const std::vector<T>& values) {
  const auto path = (dir / name).string();
  std::ofstream out(path, std::ios::binary);
  for (const T& v : values) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
    out.write(reinterpret_cast<const char*>(bytes), sizeof(T));
  }
  return path;
}

TEST(RawVolumeName, ParsesTheConvention) {
  const auto n = parseRawVolumeName("/some/dir/fuel_64x64x64_uint8.raw");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->name, "fuel");
  EXPECT_EQ(n->dims, (Index3{64, 64, 64}));
  EXPECT_EQ(n->dtype, "uint8");

  const auto m = parseRawVolumeName("my_data_v2_3x4x5_float32.raw");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->name, "my_data_v2");
  EXPECT_EQ(m->dims, (Index3{3, 4, 5}));
  EXPECT_EQ(m->dtype, "float32");

  EXPECT_TRUE(parseRawVolumeName("chameleon_1024x1024x1080_UINT16.RAW"));
}

TEST(RawVolumeName, RejectsOtherNames) {
  EXPECT_FALSE(parseRawVolumeName("fuel.raw"));
  EXPECT_FALSE(parseRawVolumeName("fuel_64x64_uint8.raw"));
  EXPECT_FALSE(parseRawVolumeName("fuel_64x64x64.raw"));
  EXPECT_FALSE(parseRawVolumeName("_64x64x64_uint8.raw"));
  EXPECT_FALSE(parseRawVolumeName("fuel_64x64x64_uint8.dat"));
  EXPECT_FALSE(parseRawVolumeName("fuel_99999999999999999999x1x1_uint8.raw"));
}

TEST(RawVolumeName, KnowsTheSampleSizes) {
  EXPECT_EQ(rawSampleSize("uint8"), 1);
  EXPECT_EQ(rawSampleSize("int8"), 1);
  EXPECT_EQ(rawSampleSize("uint16"), 2);
  EXPECT_EQ(rawSampleSize("int16"), 2);
  EXPECT_EQ(rawSampleSize("uint32"), 4);
  EXPECT_EQ(rawSampleSize("int32"), 4);
  EXPECT_EQ(rawSampleSize("float32"), 4);
  EXPECT_EQ(rawSampleSize("float64"), 8);
  EXPECT_EQ(rawSampleSize("float16"), 0);
  EXPECT_EQ(rawSampleSize(""), 0);
}

// 3x2x2 samples; the values exercise the ends of each type's range. Samples are held as float32:
// integers beyond 2^24 and float64 values come back rounded to the nearest float.
template <typename T>
void checkRoundTrip(const std::string& dtype, const std::vector<T>& values) {
  SCOPED_TRACE(dtype);
  ASSERT_EQ(values.size(), 12u);
  const auto path = writeRaw(test::scratchDir(), "vol_3x2x2_" + dtype + ".raw", values);
  const StructuredGrid g = loadStructuredVolume(path);
  EXPECT_EQ(g.dims, (Index3{3, 2, 2}));
  EXPECT_EQ(g.origin, Vec3d::Zero());
  EXPECT_EQ(g.spacing, Vec3d::Ones());
  EXPECT_EQ(g.sampleType, dtype);
  EXPECT_EQ(g.inputBytes, static_cast<std::int64_t>(12 * sizeof(T)));
  EXPECT_EQ(g.source, path);
  EXPECT_TRUE(g.fieldName.empty());
  ASSERT_EQ(g.values.size(), 12u);
  for (size_t n = 0; n < 12; ++n) EXPECT_EQ(g.values[n], static_cast<float>(values[n])) << n;
  // x fastest: sample (1,0,0) is the second value, (0,1,0) the fourth, (0,0,1) the seventh.
  EXPECT_EQ(g.at(1, 0, 0), static_cast<float>(values[1]));
  EXPECT_EQ(g.at(0, 1, 0), static_cast<float>(values[3]));
  EXPECT_EQ(g.at(0, 0, 1), static_cast<float>(values[6]));
}

TEST(RawVolumeReader, ReadsEverySampleType) {
  checkRoundTrip<std::uint8_t>("uint8", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 254, 255});
  checkRoundTrip<std::int8_t>("int8", {-128, -1, 0, 1, 2, 3, 4, 5, 6, 7, 126, 127});
  checkRoundTrip<std::uint16_t>("uint16", {0, 1, 256, 257, 1000, 5, 6, 7, 8, 9, 65534, 65535});
  checkRoundTrip<std::int16_t>("int16", {-32768, -1, 0, 1, 256, -256, 4, 5, 6, 7, 32766, 32767});
  checkRoundTrip<std::uint32_t>("uint32",
                                {0, 1, 65536, 16777217, 4, 5, 6, 7, 8, 9, 10, 4294967295u});
  checkRoundTrip<std::int32_t>(
      "int32", {std::numeric_limits<std::int32_t>::min(), -1, 0, 1, 70000, -70000, 4, 5, 6, 7, 8,
                std::numeric_limits<std::int32_t>::max()});
  checkRoundTrip<float>("float32",
                        {-1.5f, 0.0f, 0.1f, 1e-30f, 3.4e38f, -2.25f, 6, 7, 8, 9, 10, 11});
  checkRoundTrip<double>("float64", {0.1, -0.3, 1e-300, 3e38, 4, 5, 6, 7, 8, 9, 10, 11});
}

// A float64 sample beyond the float32 range cannot be held: a clear error naming the sample.
TEST(RawVolumeReader, Float64BeyondFloat32RangeIsRefused) {
  const auto path = writeRaw<double>(test::scratchDir(), "vol_2x1x1_float64.raw",
                                     std::vector<double>{1.0, 1e300});
  expectError([&] { loadStructuredVolume(path); }, {path, "sample (1, 0, 0)", "float32 range"});
}

// Out-of-core reads: any box of the file is the same box of the whole volume, whether it is
// whole planes, whole rows or neither.
TEST(RawVolumeSource, ReadsAnyBoxAsTheWholeVolumeHoldsIt) {
  std::vector<std::int16_t> values(7 * 5 * 4);
  for (size_t n = 0; n < values.size(); ++n)
    values[n] = static_cast<std::int16_t>(n * 37 % 301 - 150);
  const auto path = writeRaw<std::int16_t>(test::scratchDir(), "box_7x5x4_int16.raw", values);
  const StructuredGrid whole = readRawVolume(path);
  auto source = openRawVolume(path);
  source->setPlacement({1, 2, 3}, {0.5, 1, 2});
  EXPECT_EQ(source->layout().dims, (Index3{7, 5, 4}));
  EXPECT_EQ(source->layout().sampleType, "int16");
  EXPECT_EQ(source->layout().inputBytes, 280);
  for (const SampleRange& r : {wholeRange(whole.dims), SampleRange{{0, 0, 1}, {6, 4, 2}},
                               SampleRange{{0, 1, 0}, {6, 3, 3}}, SampleRange{{2, 1, 1}, {5, 4, 3}},
                               SampleRange{{6, 4, 3}, {6, 4, 3}}}) {
    const StructuredGrid box = source->read(r);
    EXPECT_EQ(box.values, subGrid(whole, r).values);
    EXPECT_EQ(box.origin, Vec3d(1 + 0.5 * r.lo[0], 2 + r.lo[1], 3 + 2.0 * r.lo[2]));
  }
  EXPECT_EQ(source->valueRange(), (std::pair<double, double>(-150, 150)));
  EXPECT_THROW(source->read({{0, 0, 0}, {7, 4, 3}}), Error);  // one past the last x
}

// The same reader serves payloads after a header, in either byte order.
TEST(RawVolumeSource, ReadsBigEndianSamplesAfterAnOffset) {
  const auto dir = test::scratchDir();
  const std::vector<float> values{1.5f, -2.0f, 3.25f, 1e-3f, 7.0f, -8.5f};
  {
    std::ofstream out(dir / "payload.bin", std::ios::binary);
    out.write("HDR", 3);
    for (float v : values) {
      unsigned char b[4];
      std::memcpy(b, &v, 4);
      if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + 4);
      out.write(reinterpret_cast<const char*>(b), 4);
    }
  }
  StructuredGrid layout;
  layout.dims = {3, 2, 1};
  RawVolumeSource source({(dir / "payload.bin").string(), 3, "float32", true}, layout);
  EXPECT_EQ(source.read(wholeRange(layout.dims)).values, values);
  EXPECT_EQ(source.valueRange(), (std::pair<double, double>(-8.5, 7.0)));
  // A payload that ends early is refused before any reading.
  layout.dims = {3, 2, 2};
  expectError(
      [&] {
        RawVolumeSource({(dir / "payload.bin").string(), 3, "float32", true}, layout);
      },
      {"payload.bin", "ends before the last of its 12 float32 samples"});
}

// A NaN found by the value-range pass (the first pass of out-of-core encoding) names its sample.
TEST(RawVolumeSource, ValueRangeNamesANonFiniteSample) {
  const auto path = writeRaw<float>(test::scratchDir(), "nan_3x2x2_float32.raw",
                                    {0, 1, 2, 3, 4, 5, 6, NAN, 8, 9, 10, 11});
  auto source = openRawVolume(path);
  expectError([&] { source->valueRange(); }, {path, "sample (1, 0, 1)", "NaN"});
  expectError([&] { source->read({{0, 0, 1}, {2, 1, 1}}); }, {"sample (1, 0, 0)"});
}

TEST(RawVolumeReader, SizeMismatchStatesBothSizes) {
  const auto path = writeRaw<std::uint16_t>(test::scratchDir(), "vol_4x4x4_uint16.raw",
                                            std::vector<std::uint16_t>(60, 1));
  expectError([&] { loadStructuredVolume(path); },
              {path, "120 bytes", "128 bytes", "4x4x4 uint16"});
}

TEST(RawVolumeReader, BadNameExplainsTheConvention) {
  const auto path =
      writeRaw<std::uint8_t>(test::scratchDir(), "volume.raw", std::vector<std::uint8_t>(8, 1));
  expectError([&] { loadStructuredVolume(path); },
              {path, "NAME_XxYxZ_TYPE.raw", "fuel_64x64x64_uint8.raw", "float32"});
}

TEST(RawVolumeReader, UnknownTypeListsTheKnownOnes) {
  const auto path = writeRaw<std::uint16_t>(test::scratchDir(), "vol_2x2x2_float16.raw",
                                            std::vector<std::uint16_t>(8, 1));
  expectError([&] { loadStructuredVolume(path); },
              {path, "'float16'", "uint8, int8, uint16, int16, uint32, int32, float32, float64"});
}

TEST(RawVolumeReader, ZeroDimensionIsAnError) {
  const auto path = writeRaw<std::uint8_t>(test::scratchDir(), "vol_0x2x2_uint8.raw", {});
  expectError([&] { loadStructuredVolume(path); }, {path, "0x2x2", "at least 1"});
}

TEST(RawVolumeReader, NaNSampleIsAnError) {
  std::vector<float> values(8, 1.0f);
  values[5] = std::numeric_limits<float>::quiet_NaN();
  const auto path = writeRaw(test::scratchDir(), "vol_2x2x2_float32.raw", values);
  // Sample 5 is (1, 0, 1).
  expectError([&] { loadStructuredVolume(path); }, {path, "(1, 0, 1)", "NaN"});
}

TEST(RawVolumeReader, InfSampleIsAnError) {
  std::vector<double> values(8, 1.0);
  values[0] = -std::numeric_limits<double>::infinity();
  const auto path = writeRaw(test::scratchDir(), "vol_2x2x2_float64.raw", values);
  expectError([&] { loadStructuredVolume(path); }, {path, "(0, 0, 0)"});
}

TEST(RawVolumeReader, OptionsOverrideSpacingAndOrigin) {
  const auto path =
      writeRaw<std::uint8_t>(test::scratchDir(), "vol_2x2x2_uint8.raw", {1, 2, 3, 4, 5, 6, 7, 8});
  VolumeLoadOptions options;
  options.spacing = Vec3d(0.5, 2.0, 3.0);
  options.origin = Vec3d(-1.0, 0.0, 10.0);
  const StructuredGrid g = loadStructuredVolume(path, options);
  EXPECT_EQ(g.spacing, Vec3d(0.5, 2.0, 3.0));
  EXPECT_EQ(g.origin, Vec3d(-1.0, 0.0, 10.0));
  EXPECT_EQ(g.boxMax(), Vec3d(-0.5, 2.0, 13.0));
}

TEST(RawVolumeReader, NonPositiveSpacingOverrideIsAnError) {
  const auto path =
      writeRaw<std::uint8_t>(test::scratchDir(), "vol_2x2x2_uint8.raw", {1, 2, 3, 4, 5, 6, 7, 8});
  VolumeLoadOptions options;
  options.spacing = Vec3d(1.0, 0.0, 1.0);
  expectError([&] { loadStructuredVolume(path, options); }, {path, "spacing"});
  options.spacing = Vec3d(1.0, 1.0, std::numeric_limits<double>::infinity());
  expectError([&] { loadStructuredVolume(path, options); }, {path, "spacing"});
}

TEST(RawVolumeReader, FieldNameIsAnErrorForRaw) {
  const auto path =
      writeRaw<std::uint8_t>(test::scratchDir(), "vol_2x2x2_uint8.raw", {1, 2, 3, 4, 5, 6, 7, 8});
  VolumeLoadOptions options;
  options.field.name = "density";
  expectError([&] { loadStructuredVolume(path, options); }, {path, "'density'"});
}

TEST(RawVolumeReader, RealFuel) {
  const auto path = test::dataFile("fuel_64x64x64_uint8.raw");
  if (path.empty()) GTEST_SKIP() << "fuel_64x64x64_uint8.raw not in " << test::dataDir();
  const StructuredGrid g = loadStructuredVolume(path.string());
  EXPECT_EQ(g.dims, (Index3{64, 64, 64}));
  EXPECT_EQ(g.sampleType, "uint8");
  EXPECT_EQ(g.inputBytes, 64 * 64 * 64);
  const auto [lo, hi] = std::minmax_element(g.values.begin(), g.values.end());
  EXPECT_EQ(*lo, 0.0);
  EXPECT_EQ(*hi, 255.0);
}

TEST(RawVolumeReader, RealNucleon) {
  const auto path = test::dataFile("nucleon_41x41x41_uint8.raw");
  if (path.empty()) GTEST_SKIP() << "nucleon_41x41x41_uint8.raw not in " << test::dataDir();
  const StructuredGrid g = loadStructuredVolume(path.string());
  EXPECT_EQ(g.dims, (Index3{41, 41, 41}));
  EXPECT_EQ(g.values.size(), 41u * 41u * 41u);
  const auto [lo, hi] = std::minmax_element(g.values.begin(), g.values.end());
  EXPECT_EQ(*lo, 0.0);
  EXPECT_EQ(*hi, 249.0);
}

}  // namespace
}  // namespace mfadvr
