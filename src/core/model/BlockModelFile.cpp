#include "core/model/BlockModelFile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/model/ModelFile.h"
#include "core/util/AtomicFile.h"
#include "core/util/ByteIo.h"
#include "core/util/Crc32.h"
#include "core/util/Error.h"

namespace mfadvr {
namespace {

using nlohmann::json;

constexpr char kMagic[12] = {'M', 'F', 'A', 'D', 'V', 'R', 'M', 'B', '\r', '\n', '\x1a', '\n'};
constexpr size_t kPrefixBytes = sizeof(kMagic) + 4 + 4;  // magic, version, index length
constexpr std::uint32_t kMaxIndexBytes = 64u << 20;

json boxJson(const DomainBox& b) {
  return {b.min[0], b.max[0], b.min[1], b.max[1], b.min[2], b.max[2]};
}

DomainBox boxOf(const json& j) {
  const auto a = j.get<std::array<double, 6>>();
  DomainBox b{Vec3d(a[0], a[2], a[4]), Vec3d(a[1], a[3], a[5])};
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(a[i])) throw Error("a box is not finite");
  if (!((b.max.array() >= b.min.array()).all())) throw Error("a box has min > max");
  return b;
}

std::uint64_t unsignedOf(const json& j, const char* key) {
  const json& v = j.at(key);
  if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<std::int64_t>() >= 0))
    throw Error(std::string(key) + " must be a non-negative integer");
  return v.get<std::uint64_t>();
}

std::vector<std::uint8_t> readRange(const std::filesystem::path& path, std::uint64_t offset,
                                    std::uint64_t bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path.string() + ": " + std::strerror(errno));
  in.seekg(static_cast<std::streamoff>(offset));
  std::vector<std::uint8_t> out(static_cast<size_t>(bytes));
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(bytes));
  if (static_cast<std::uint64_t>(in.gcount()) != bytes)
    throw Error("cannot read " + path.string() + ": the file is shorter than its index says");
  return out;
}

// The JSON index of blocks whose models have `sizes` bytes, the first at byte `first`.
std::string indexText(const Index3& grid, const DomainBox& whole, double valueMin, double valueMax,
                      const std::vector<DomainBox>& regions,
                      const std::vector<std::uint64_t>& sizes, std::uint64_t first) {
  json entries = json::array();
  std::uint64_t offset = first;
  for (size_t i = 0; i < regions.size(); ++i) {
    entries.push_back({{"region", boxJson(regions[i])}, {"offset", offset}, {"bytes", sizes[i]}});
    offset += sizes[i];
  }
  return json{{"format", "mfadvr-blocks"},
              {"blocks", grid},
              {"box", boxJson(whole)},
              {"value_range", {valueMin, valueMax}},
              {"entries", entries}}
      .dump();
}

// Magic, version, index length, index and checksum: every byte before the first block.
std::string indexHead(const std::string& index) {
  std::string out;
  out.append(kMagic, sizeof(kMagic));
  appendBytes(out, kBlockFormatVersion);
  appendBytes(out, static_cast<std::uint32_t>(index.size()));
  out += index;
  appendBytes(out, crc32Of(reinterpret_cast<const std::uint8_t*>(out.data()), out.size()));
  return out;
}

DomainBox unionOf(const std::vector<DomainBox>& regions) {
  DomainBox whole = regions.front();
  for (const DomainBox& r : regions) {
    whole.min = whole.min.cwiseMin(r.min);
    whole.max = whole.max.cwiseMax(r.max);
  }
  return whole;
}

void requireBlockCount(const Index3& grid, size_t count) {
  if (count == 0) throw Error("a multi-block model needs at least one block");
  if (static_cast<std::int64_t>(count) > kMaxBlockCount)
    throw Error("a multi-block model holds at most " + std::to_string(kMaxBlockCount) + " blocks");
  if (grid[0] * grid[1] * grid[2] != static_cast<std::int64_t>(count))
    throw Error("internal: the block grid does not match the number of blocks");
}

}  // namespace

bool isBlockModelFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[sizeof(kMagic)] = {};
  in.read(magic, sizeof(magic));
  return in && std::memcmp(magic, kMagic, sizeof(kMagic)) == 0;
}

std::string serializeBlockModels(const std::vector<ModelBlock>& blocks, const Index3& grid) {
  requireBlockCount(grid, blocks.size());
  std::vector<std::string> models;
  std::vector<DomainBox> regions;
  std::vector<std::uint64_t> sizes;
  for (const ModelBlock& b : blocks) {
    models.push_back(serializeModel(b.model));
    regions.push_back(b.region);
    sizes.push_back(models.back().size());
  }
  const DomainBox whole = unionOf(regions);
  const double vmin = blocks.front().model.valueMin(), vmax = blocks.front().model.valueMax();
  // Offsets depend on the index's length, which depends on the offsets' digits: lay out with a
  // guess and repeat until the length is stable (twice at most in practice).
  std::string index;
  std::uint64_t first = 0;
  for (int pass = 0; pass < 8; ++pass) {
    index = indexText(grid, whole, vmin, vmax, regions, sizes, first);
    const std::uint64_t needed = kPrefixBytes + index.size() + 4;
    if (needed == first) break;
    first = needed;
  }
  std::string out = indexHead(index);
  if (out.size() != first) throw Error("internal: the block index did not settle");
  for (const std::string& m : models) out += m;
  return out;
}

BlockModelFileWriter::BlockModelFileWriter(const std::filesystem::path& path, const Index3& grid)
    : file_(path), grid_(grid) {
  requireBlockCount(grid, static_cast<size_t>(grid[0] * grid[1] * grid[2]));
  // Room for the longest index these blocks can have: every double at its longest (24
  // characters), and offsets and sizes, laid out here as 0, at 20 digits each. The index written
  // at the end is padded to this length with spaces, which JSON ignores, so the blocks never move.
  const double longest = -1.2345678901234567e-300;
  const std::vector<DomainBox> regions(
      static_cast<size_t>(grid[0] * grid[1] * grid[2]),
      DomainBox{Vec3d::Constant(longest), Vec3d::Constant(longest)});
  const std::vector<std::uint64_t> zeros(regions.size(), 0);
  indexBytes_ = indexText(grid, regions.front(), longest, longest, regions, zeros, 0).size() +
                2 * 19 * regions.size();
  if (indexBytes_ > kMaxIndexBytes) throw Error("too many blocks for one multi-block file");
  file_.write(std::string(kPrefixBytes + indexBytes_ + 4, '\0'));
}

void BlockModelFileWriter::append(const ModelBlock& block) {
  if (regions_.size() == static_cast<size_t>(grid_[0] * grid_[1] * grid_[2]))
    throw Error("internal: more blocks than the block grid holds");
  if (regions_.empty()) {
    valueMin_ = block.model.valueMin();
    valueMax_ = block.model.valueMax();
  }
  const std::string bytes = serializeModel(block.model);
  file_.write(bytes);
  regions_.push_back(block.region);
  sizes_.push_back(bytes.size());
}

void BlockModelFileWriter::commit() {
  requireBlockCount(grid_, regions_.size());
  std::string index = indexText(grid_, unionOf(regions_), valueMin_, valueMax_, regions_, sizes_,
                                kPrefixBytes + indexBytes_ + 4);
  if (index.size() > indexBytes_) throw Error("internal: the block index outgrew its room");
  index.append(indexBytes_ - index.size(), ' ');
  file_.writeAt(0, indexHead(index));
  file_.commit();
}

void saveBlockModels(const std::vector<ModelBlock>& blocks, const Index3& grid,
                     const std::filesystem::path& path) {
  writeFileAtomically(path, serializeBlockModels(blocks, grid));
}

BlockIndex parseBlockIndex(std::span<const std::uint8_t> b, std::uint64_t fileBytes,
                           const std::string& name) {
  auto bad = [&](const std::string& why) {
    return Error(name + ": not a valid multi-block .mfa model: " + why);
  };
  if (b.size() < sizeof(kMagic) || std::memcmp(b.data(), kMagic, sizeof(kMagic)) != 0)
    throw Error(name + ": not a multi-block .mfa model (wrong magic bytes)");
  if (b.size() < kPrefixBytes) throw bad("file is truncated");
  const auto version = readBytesAt<std::uint32_t>(b, sizeof(kMagic));
  if (version != kBlockFormatVersion)
    throw Error(name + ": multi-block format version " + std::to_string(version) +
                " is not supported; this build reads version " +
                std::to_string(kBlockFormatVersion));
  const auto indexBytes = readBytesAt<std::uint32_t>(b, sizeof(kMagic) + 4);
  if (indexBytes > kMaxIndexBytes || kPrefixBytes + indexBytes + 4 > b.size())
    throw bad("index length " + std::to_string(indexBytes) + " does not fit the file");
  const size_t crcAt = kPrefixBytes + indexBytes;
  if (crc32Of(b.data(), crcAt) != readBytesAt<std::uint32_t>(b, crcAt))
    throw bad("index checksum mismatch (file is corrupted)");

  BlockIndex index;
  index.indexBytes = crcAt + 4;
  try {
    const json h = json::parse(b.begin() + kPrefixBytes, b.begin() + crcAt);
    if (!h.is_object() || h.value("format", "") != "mfadvr-blocks")
      throw bad("index is not an mfadvr-blocks index");
    const json& grid = h.at("blocks");
    if (!grid.is_array() || grid.size() != 3) throw bad("blocks must be 3 integers");
    std::int64_t count = 1;
    for (int a = 0; a < 3; ++a) {
      if (!grid[a].is_number_integer()) throw bad("blocks must be 3 integers");
      index.blocks[a] = grid[a].get<std::int64_t>();
      if (index.blocks[a] < 1 || index.blocks[a] > kMaxBlockCount)
        throw bad("block counts must be between 1 and " + std::to_string(kMaxBlockCount));
      count *= index.blocks[a];
      if (count > kMaxBlockCount) throw bad("too many blocks");
    }
    index.box = boxOf(h.at("box"));
    const auto range = h.at("value_range").get<std::array<double, 2>>();
    if (!(std::isfinite(range[0]) && std::isfinite(range[1]) && range[0] <= range[1]))
      throw bad("value range is not finite");
    index.valueMin = range[0];
    index.valueMax = range[1];
    const json& entries = h.at("entries");
    if (!entries.is_array() || static_cast<std::int64_t>(entries.size()) != count)
      throw bad("the index must list " + std::to_string(count) + " blocks");
    std::uint64_t next = index.indexBytes;
    for (const json& e : entries) {
      BlockEntry entry;
      entry.region = boxOf(e.at("region"));
      if (!((entry.region.min.array() >= index.box.min.array()).all() &&
            (entry.region.max.array() <= index.box.max.array()).all()))
        throw bad("a block's region lies outside the box");
      entry.offset = unsignedOf(e, "offset");
      entry.bytes = unsignedOf(e, "bytes");
      if (entry.offset != next || entry.bytes == 0 || entry.bytes > fileBytes - next)
        throw bad("block offsets and sizes do not follow each other through the file");
      next += entry.bytes;
      index.entries.push_back(entry);
    }
    if (next != fileBytes)
      throw bad("the blocks end at byte " + std::to_string(next) + " but the file has " +
                std::to_string(fileBytes) + (next < fileBytes ? " (trailing bytes)" : ""));
  } catch (const json::exception& e) {
    throw bad(std::string("index is corrupt (") + e.what() + ")");
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(name, 0) == 0) throw;
    throw bad(what);
  }
  return index;
}

BlockIndex readBlockIndex(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error("cannot read " + path.string() + ": is a directory");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw Error("cannot read " + path.string() + ": " + ec.message());
  const auto prefix = readRange(path, 0, std::min<std::uint64_t>(size, kPrefixBytes));
  std::uint64_t headBytes = prefix.size();
  if (prefix.size() == kPrefixBytes && std::memcmp(prefix.data(), kMagic, sizeof(kMagic)) == 0)
    headBytes = std::min<std::uint64_t>(
        size, kPrefixBytes +
                  std::min<std::uint64_t>(readBytesAt<std::uint32_t>(prefix, 16), kMaxIndexBytes) +
                  4);
  return parseBlockIndex(readRange(path, 0, headBytes), size, path.string());
}

namespace {

// owner: as parseModel's (the block's float32 control points used where they were read).
Model parseBlock(std::span<const std::uint8_t> bytes, const BlockEntry& e, const std::string& name,
                 std::shared_ptr<const void> owner = nullptr) {
  Model m = parseModel(bytes, name, nullptr, std::move(owner));
  // Up to rounding (a writer computes both from the same grid, along different sums).
  const DomainBox& d = m.domain();
  const Vec3d slack = 1e-9 * d.extent();
  if (!((e.region.min.array() >= (d.min - slack).array()).all() &&
        (e.region.max.array() <= (d.max + slack).array()).all()))
    throw Error(name + ": the block's region lies outside its model's box");
  return m;
}

}  // namespace

std::vector<ModelFileSummary> summarizeBlocks(const std::filesystem::path& path,
                                              const BlockIndex& index) {
  std::vector<ModelFileSummary> out;
  out.reserve(index.entries.size());
  for (const BlockEntry& e : index.entries)
    out.push_back(summarizeModelFile(path, e.offset, e.bytes));
  return out;
}

Model loadBlock(const std::filesystem::path& path, const BlockIndex& index, size_t i) {
  if (i >= index.entries.size()) throw Error("block index out of range");
  const BlockEntry& e = index.entries[i];
  auto bytes =
      std::make_shared<const std::vector<std::uint8_t>>(readRange(path, e.offset, e.bytes));
  const std::span<const std::uint8_t> view(*bytes);
  return parseBlock(view, e, path.string() + " (block " + std::to_string(i) + ")",
                    std::move(bytes));
}

std::vector<ModelBlock> parseBlockModels(std::span<const std::uint8_t> bytes,
                                         const std::string& name) {
  const BlockIndex index = parseBlockIndex(bytes, bytes.size(), name);
  std::vector<ModelBlock> out;
  for (size_t i = 0; i < index.entries.size(); ++i) {
    const BlockEntry& e = index.entries[i];
    out.push_back({e.region, parseBlock(bytes.subspan(e.offset, e.bytes), e,
                                        name + " (block " + std::to_string(i) + ")")});
  }
  return out;
}

std::vector<ModelBlock> loadBlockModels(const std::filesystem::path& path) {
  const BlockIndex index = readBlockIndex(path);
  std::vector<ModelBlock> out;
  for (size_t i = 0; i < index.entries.size(); ++i)
    out.push_back({index.entries[i].region, loadBlock(path, index, i)});
  return out;
}

}  // namespace mfadvr
