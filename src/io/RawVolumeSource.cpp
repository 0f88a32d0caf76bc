#include "io/RawVolumeSource.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"
#include "io/RawVolumeReader.h"

namespace mfadvr {
namespace {

// Samples converted per read: large enough for the disk, small beside any volume.
constexpr std::int64_t kChunkSamples = std::int64_t{1} << 20;

template <typename T>
T load(const unsigned char* bytes, bool swap) {
  unsigned char buf[sizeof(T)];
  if (swap) {
    for (size_t b = 0; b < sizeof(T); ++b) buf[b] = bytes[sizeof(T) - 1 - b];
  } else {
    std::memcpy(buf, bytes, sizeof(T));
  }
  T value;
  std::memcpy(&value, buf, sizeof(T));
  return value;
}

template <typename T>
void convert(const unsigned char* bytes, size_t count, bool swap, float* out) {
  for (size_t n = 0; n < count; ++n)
    out[n] = static_cast<float>(load<T>(bytes + n * sizeof(T), swap));
}

void convertSamples(const std::string& dtype, const unsigned char* bytes, size_t count, bool swap,
                    float* out) {
  if (dtype == "uint8") return convert<std::uint8_t>(bytes, count, swap, out);
  if (dtype == "int8") return convert<std::int8_t>(bytes, count, swap, out);
  if (dtype == "uint16") return convert<std::uint16_t>(bytes, count, swap, out);
  if (dtype == "int16") return convert<std::int16_t>(bytes, count, swap, out);
  if (dtype == "uint32") return convert<std::uint32_t>(bytes, count, swap, out);
  if (dtype == "int32") return convert<std::int32_t>(bytes, count, swap, out);
  if (dtype == "float32") return convert<float>(bytes, count, swap, out);
  if (dtype == "float64") return convert<double>(bytes, count, swap, out);
  throw Error("internal: no conversion for sample type " + dtype);
}

// Calls run(first, count) for the runs of consecutive file samples that make up `range`, in
// the order of the range's samples (x fastest): whole rows, or whole planes, lie one after
// another in the file and are one run.
template <typename Run>
void forEachRun(const Index3& d, const SampleRange& range, Run&& run) {
  const Index3 r = range.dims();
  const bool wholeRows = r[0] == d[0], wholePlanes = wholeRows && r[1] == d[1];
  if (wholePlanes) return run(d[0] * d[1] * range.lo[2], range.sampleCount());
  for (std::int64_t k = range.lo[2]; k <= range.hi[2]; ++k) {
    const std::int64_t row = range.lo[0] + d[0] * (range.lo[1] + d[1] * k);
    if (wholeRows) {
      run(row, r[0] * r[1]);
      continue;
    }
    for (std::int64_t j = 0; j < r[1]; ++j) run(row + d[0] * j, r[0]);
  }
}

}  // namespace

RawVolumeSource::RawVolumeSource(RawSampleLayout file, const StructuredGrid& grid)
    : file_(std::move(file)) {
  layout_ = grid;
  layout_.values.clear();
  layout_.values.shrink_to_fit();
  if (layout_.source.empty()) layout_.source = file_.path;
  layout_.sampleType = file_.dtype;
  sampleBytes_ = rawSampleSize(file_.dtype);
  if (sampleBytes_ == 0) throw Error(file_.path + ": unknown sample type '" + file_.dtype + "'");
  for (int a = 0; a < 3; ++a)
    if (layout_.dims[a] < 1) throw Error(file_.path + ": grid dimensions must be at least 1");
  std::int64_t bytes = sampleBytes_;
  for (int a = 0; a < 3; ++a)
    if (__builtin_mul_overflow(bytes, layout_.dims[a], &bytes))
      throw Error(file_.path + ": the declared grid is too large");
  layout_.inputBytes = bytes;
  fd_ = ::open(file_.path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error("cannot open " + file_.path + ": " + std::strerror(errno));
  const off_t size = ::lseek(fd_, 0, SEEK_END);
  if (size < 0 || file_.offset < 0 || size - file_.offset < bytes) {
    ::close(fd_);
    fd_ = -1;
    throw Error(file_.path + ": the file ends before the last of its " +
                std::to_string(layout_.sampleCount()) + " " + file_.dtype + " samples");
  }
}

RawVolumeSource::~RawVolumeSource() {
  if (fd_ >= 0) ::close(fd_);
}

void RawVolumeSource::setPlacement(const Vec3d& origin, const Vec3d& spacing) {
  layout_.origin = origin;
  layout_.spacing = spacing;
}

void RawVolumeSource::readBytes(std::int64_t first, std::int64_t count, unsigned char* out) {
  const size_t want = static_cast<size_t>(count) * static_cast<size_t>(sampleBytes_);
  const off_t at = static_cast<off_t>(file_.offset + first * sampleBytes_);
  size_t got = 0;
  while (got < want) {
    const ssize_t r = ::pread(fd_, out + got, want - got, at + static_cast<off_t>(got));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0)
      throw Error("cannot read " + file_.path + ": " +
                  (r < 0 ? std::strerror(errno) : "unexpected end of file"));
    got += static_cast<size_t>(r);
  }
}

bool RawVolumeSource::swapsBytes() const {
  return sampleBytes_ > 1 && file_.bigEndian != (std::endian::native == std::endian::big);
}

void RawVolumeSource::readRun(std::int64_t first, std::int64_t count, float* out) {
  while (count > 0) {
    const std::int64_t n = std::min(count, kChunkSamples);
    buffer_.resize(std::max(buffer_.size(), static_cast<size_t>(n * sampleBytes_)));
    readBytes(first, n, buffer_.data());
    convertSamples(file_.dtype, buffer_.data(), static_cast<size_t>(n), swapsBytes(), out);
    if (file_.calibrated())
      for (std::int64_t s = 0; s < n; ++s)
        out[s] = static_cast<float>(out[s] * file_.scale + file_.shift);
    first += n;
    count -= n;
    out += n;
  }
}

StructuredGrid RawVolumeSource::readUnchecked(const SampleRange& range) {
  StructuredGrid g = subGridLayout(layout_, range);
  requireMemory(std::int64_t(sizeof(float)) * g.sampleCount(),
                "reading " + file_.path + " (its samples are held as float32)");
  g.values.resize(static_cast<size_t>(g.sampleCount()));
  readFloats(range, g.values.data());
  return g;
}

void RawVolumeSource::readFloats(const SampleRange& range, float* out) {
  requireRangeInside(range, layout_.dims);
  forEachRun(layout_.dims, range, [&](std::int64_t first, std::int64_t count) {
    readRun(first, count, out);
    out += count;
  });
}

void RawVolumeSource::readStored(const SampleRange& range, void* out) {
  requireRangeInside(range, layout_.dims);
  auto* bytes = static_cast<unsigned char*>(out);
  forEachRun(layout_.dims, range, [&](std::int64_t first, std::int64_t count) {
    readBytes(first, count, bytes);
    const size_t size = static_cast<size_t>(count) * static_cast<size_t>(sampleBytes_);
    if (swapsBytes())
      for (size_t at = 0; at < size; at += static_cast<size_t>(sampleBytes_))
        std::reverse(bytes + at, bytes + at + sampleBytes_);
    bytes += size;
  });
}

StructuredGrid RawVolumeSource::read(const SampleRange& range) {
  StructuredGrid g = readUnchecked(range);
  g.validate();
  return g;
}

std::pair<double, double> RawVolumeSource::valueRange() {
  if (haveRange_) return range_;
  std::vector<float> chunk(static_cast<size_t>(std::min(kChunkSamples, layout_.sampleCount())));
  float lo = INFINITY, hi = -INFINITY;
  for (std::int64_t first = 0; first < layout_.sampleCount(); first += kChunkSamples) {
    const std::int64_t n = std::min(kChunkSamples, layout_.sampleCount() - first);
    readRun(first, n, chunk.data());
    for (std::int64_t s = 0; s < n; ++s) {
      const float v = chunk[static_cast<size_t>(s)];
      if (!std::isfinite(v)) throw Error(nonFiniteSampleMessage(layout_, first + s, v));
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  range_ = {lo, hi};
  haveRange_ = true;
  return range_;
}

}  // namespace mfadvr
