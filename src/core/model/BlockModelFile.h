#pragma once
// The multi-block model file: several MFA models, each with the region of the domain it renders
// (one piece of a partitioned volume, fitted with ghost layers around it), in one file that a
// parallel reader reads block by block. docs/model-format.md describes every byte:
//
//   magic "MFADVRMB\r\n\x1a\n" (12 bytes) | u32 version (1) | u32 index length H | H bytes JSON
//   index | u32 CRC-32 of every byte before it | block 0 (a complete .mfa model) | block 1 | ...
//
// The index gives the block grid, the whole box, the whole value range and, per block, its
// region and the offset and size of its model. Each block is a complete .mfa model with its own
// checksum, read only by the rank that renders it.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/model/Model.h"
#include "core/model/ModelFile.h"
#include "core/util/AtomicFile.h"

namespace mfadvr {

inline constexpr std::uint32_t kBlockFormatVersion = 1;
// The most blocks a file may hold (readers refuse more).
inline constexpr std::int64_t kMaxBlockCount = std::int64_t{1} << 20;

// A model and the region it renders (inside the model's box; the regions of a file's blocks
// tile its whole box without overlapping).
struct ModelBlock {
  DomainBox region;
  Model model;
};

struct BlockEntry {
  DomainBox region;
  std::uint64_t offset = 0;  // of the block's model, from the start of the file
  std::uint64_t bytes = 0;
};

struct BlockIndex {
  Index3 blocks{1, 1, 1};  // blocks per axis; entries are x fastest
  DomainBox box;           // the union of the regions
  double valueMin = 0.0, valueMax = 0.0;
  std::vector<BlockEntry> entries;
  std::uint64_t indexBytes = 0;  // bytes before the first block
};

// Whether the file starts with the multi-block magic bytes.
bool isBlockModelFile(const std::filesystem::path& path);

// blocks: per axis, entries x fastest. Writes atomically.
std::string serializeBlockModels(const std::vector<ModelBlock>& blocks, const Index3& grid);
void saveBlockModels(const std::vector<ModelBlock>& blocks, const Index3& grid,
                     const std::filesystem::path& path);

// Writes a multi-block file block by block, so that only one block is in memory at a time: room
// for the index first, then each block as it is appended, then the index (padded with spaces to
// its room) once all are there. The file appears, atomically, only on commit().
class BlockModelFileWriter {
 public:
  BlockModelFileWriter(const std::filesystem::path& path, const Index3& grid);
  // The next block in file order (x fastest); every block carries the whole value range.
  void append(const ModelBlock& block);
  void commit();  // after the last block

 private:
  AtomicFileWriter file_;
  Index3 grid_;
  size_t indexBytes_ = 0;
  double valueMin_ = 0.0, valueMax_ = 0.0;
  std::vector<DomainBox> regions_;
  std::vector<std::uint64_t> sizes_;
};

// Checks the index (magic, version, checksum, block grid, regions, offsets: contiguous blocks
// that end exactly at fileBytes) of a file of fileBytes bytes whose first bytes are `head`; the
// index must be complete in `head`. Throws mfadvr::Error naming `name`.
BlockIndex parseBlockIndex(std::span<const std::uint8_t> head, std::uint64_t fileBytes,
                           const std::string& name);
BlockIndex readBlockIndex(const std::filesystem::path& path);

// Each block's model size as its header says (only the headers are read: memory estimates).
std::vector<ModelFileSummary> summarizeBlocks(const std::filesystem::path& path,
                                              const BlockIndex& index);

// A multi-block file whose blocks are read one at a time, where they are used (rendering a
// model that does not fit in memory at once: loadBlock for each).
struct BlockModelStream {
  std::filesystem::path path;
  BlockIndex index;
};

// Block i's model (its bytes alone are read and checked).
Model loadBlock(const std::filesystem::path& path, const BlockIndex& index, size_t i);
std::vector<ModelBlock> loadBlockModels(const std::filesystem::path& path);
// Every block of a whole file in memory (tests, fuzzing).
std::vector<ModelBlock> parseBlockModels(std::span<const std::uint8_t> bytes,
                                         const std::string& name = "blocks");

}  // namespace mfadvr
