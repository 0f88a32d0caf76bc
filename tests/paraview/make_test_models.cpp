// Writes the models the ParaView plugin tests read: a single model and a 4 x 1 x 1 multi-block
// model of the same Marschner-Lobb samples (interpolating quadratic fits).
#include <cstdio>
#include <exception>
#include <filesystem>

#include "core/analytic/BuiltinFunction.h"
#include "core/encode/Encoder.h"
#include "core/encode/PieceEncoder.h"
#include "core/model/BlockModelFile.h"
#include "core/model/ModelFile.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    const mfadvr::StructuredGrid grid = mfadvr::sampleBuiltinSpec("builtin:marschner-lobb:41");
    mfadvr::EncodeOptions options;
    options.degree = {2, 2, 2};
    mfadvr::saveModel(mfadvr::encodeStructured(grid, options), dir / "single.mfa");
    mfadvr::saveBlockModels(mfadvr::encodeStructuredBlocks(grid, {4, 1, 1}, -1, options), {4, 1, 1},
                            dir / "blocks.mfa");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
