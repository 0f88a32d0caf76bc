#pragma once
// Samples stored uncompressed in a file, x fastest, one numeric type, from a byte offset on:
// headerless .raw volumes, and the payload of any header format that stores its samples this
// way. Read a box at a time, so that a volume larger than the memory can be encoded block by
// block (core/encode/PieceEncoder.h).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/grid/GridSampleSource.h"

namespace mfadvr {

struct RawSampleLayout {
  std::string path;         // the file holding the samples
  std::int64_t offset = 0;  // byte of the first sample
  std::string dtype;        // uint8, int8, uint16, int16, uint32, int32, float32, float64
  bool bigEndian = false;
  // value = stored * scale + shift (NIfTI's scl_slope, scl_inter), computed as VTK-read
  // samples are calibrated: the stored value as float32, then in double.
  double scale = 1.0;
  double shift = 0.0;
  bool calibrated() const { return scale != 1.0 || shift != 0.0; }
};

class RawVolumeSource final : public GridSampleSource {
 public:
  // `grid`: dims, placement and names (values ignored). Throws mfadvr::Error naming the file when
  // the type is unknown, the file cannot be opened, or it ends before the last sample.
  RawVolumeSource(RawSampleLayout file, const StructuredGrid& grid);
  ~RawVolumeSource() override;
  RawVolumeSource(const RawVolumeSource&) = delete;
  RawVolumeSource& operator=(const RawVolumeSource&) = delete;

  const StructuredGrid& layout() const override { return layout_; }
  // Placement given on the command line replaces the file's.
  void setPlacement(const Vec3d& origin, const Vec3d& spacing);
  StructuredGrid read(const SampleRange& range) override;
  // The samples of `range`, not checked for non-finite values (whole-volume reads, which the
  // caller validates).
  StructuredGrid readUnchecked(const SampleRange& range);
  std::pair<double, double> valueRange() override;
  // The samples of `range` (inside the grid) as float32 values, x fastest, into `out`
  // (range.sampleCount() floats), not checked.
  void readFloats(const SampleRange& range, float* out);

  // The samples as stored: `layout().sampleType`, `sampleBytes()` each. They are the values
  // unless the file calibrates them (NIfTI's scl_slope, scl_inter).
  int sampleBytes() const { return sampleBytes_; }
  bool calibrated() const { return file_.calibrated(); }
  // The stored samples of `range` (inside the grid), in this machine's byte order, x fastest,
  // into `out` (range.sampleCount() * sampleBytes() bytes), not converted: a reader can hand
  // them on in their own type.
  void readStored(const SampleRange& range, void* out);

 private:
  // `count` consecutive samples from sample index `first` of the file, as stored.
  void readBytes(std::int64_t first, std::int64_t count, unsigned char* out);
  // The same, converted to float (and calibrated).
  void readRun(std::int64_t first, std::int64_t count, float* out);
  bool swapsBytes() const;

  RawSampleLayout file_;
  StructuredGrid layout_;
  int sampleBytes_ = 0;
  int fd_ = -1;
  std::vector<unsigned char> buffer_;
  bool haveRange_ = false;
  std::pair<double, double> range_{0.0, 0.0};
};

}  // namespace mfadvr
