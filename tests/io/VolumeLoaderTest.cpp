// Dispatch of loadStructuredVolume: builtin specs, missing files, unknown extensions.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "core/util/Error.h"
#include "io/VolumeLoader.h"

namespace mfadvr {
namespace {

using test::expectError;

TEST(VolumeLoader, BuiltinSpec) {
  const StructuredGrid g = loadStructuredVolume("builtin:gaussian-beam:8");
  EXPECT_EQ(g.dims, (Index3{8, 8, 8}));
  EXPECT_EQ(g.values.size(), 512u);
  VolumeLoadOptions moved;
  moved.spacing = Vec3d(1, 1, 1);
  expectError([&] { loadStructuredVolume("builtin:gaussian-beam:8", moved); },
              {"builtin:gaussian-beam:8", "not to built-in functions"});
}

TEST(VolumeLoader, MissingFile) {
  const auto path = (test::scratchDir() / "nothing_4x4x4_uint8.raw").string();
  expectError([&] { loadStructuredVolume(path); },
              {"cannot open " + path, "No such file or directory"});
  const auto vti = (test::scratchDir() / "nothing.vti").string();
  expectError([&] { loadStructuredVolume(vti); }, {"cannot open " + vti, "No such file"});
}

TEST(VolumeLoader, DirectoryIsAnError) {
  const auto dir = test::scratchDir() / "vol.vti";
  std::filesystem::create_directories(dir);
  expectError([&] { loadStructuredVolume(dir.string()); }, {dir.string(), "directory"});
}

TEST(VolumeLoader, UnknownExtensionListsTheFormats) {
  const auto path = (test::scratchDir() / "volume.xyz").string();
  std::ofstream(path) << "data";
  expectError([&] { loadStructuredVolume(path); },
              {path, "'.xyz'", ".raw", ".nrrd", ".vti", ".vtk", ".mha", "builtin:"});
  const auto bare = (test::scratchDir() / "volume").string();
  std::ofstream(bare) << "data";
  expectError([&] { loadStructuredVolume(bare); }, {bare, "no extension"});
}

TEST(VolumeLoader, OtherVtkXmlDatasetsNeedARegularGrid) {
  const auto path = (test::scratchDir() / "mesh.vtu").string();
  std::ofstream(path) << "<VTKFile type=\"UnstructuredGrid\"/>";
  expectError([&] { loadStructuredVolume(path); }, {path, "'.vtu'", "regular grid", ".vti"});
}

TEST(VolumeLoader, ExtensionsAreCaseInsensitive) {
  const auto path = (test::scratchDir() / "v_2x1x1_uint8.RAW").string();
  std::ofstream(path, std::ios::binary) << std::string("\x01\x02", 2);
  const StructuredGrid g = loadStructuredVolume(path);
  EXPECT_EQ(g.values, (std::vector<float>{1.0f, 2.0f}));
}

TEST(VolumeLoader, SupportedFormatsText) {
  const std::string text = supportedVolumeFormats();
  for (const char* word : {".raw", "uint8", "float64", ".nrrd", ".nhdr", ".vti", ".vtk",
                           "STRUCTURED_POINTS", ".mha", ".mhd", "builtin:"})
    EXPECT_NE(text.find(word), std::string::npos) << word;
}

}  // namespace
}  // namespace mfadvr
